#pragma once
// The surface pass (paper 004 section 4, docs/viz.md "Surface"): the water surface as a mesh
// subsampled by weighted average, per-pixel normals from a full-resolution height-difference
// texture, refraction of the ground (the paper's linearised texture coordinates, recomputed when
// the view changes, or exact Snell per pixel), Fresnel reflection of the sky, the sun's glint, depth
// colour and absorption, the dye and foam the flow carries (shaders/surface.vert, surface.frag);
// and the water's sides, the mesh's outline down to the floor.
#include <span>
#include <vector>

#include "flat_drawer.hpp"
#include "gl.hpp"
#include "refraction.hpp"
#include "shading.hpp"

namespace huygens {

class SurfacePass {
 public:
  SurfacePass(const GridPlacement& grid, double ground_z, int subsample);
  ~SurfacePass();
  SurfacePass(const SurfacePass&) = delete;
  SurfacePass& operator=(const SurfacePass&) = delete;

  const SurfaceMeshLayout& layout() const { return layout_; }
  /// The mesh's heights and the height differences of `eta` (rows x cols, m, after the offset),
  /// uploaded by the next upload().
  void prepare(std::span<const float> eta);
  /// Dye and foam per grid point (rows x cols, in [0, 1]); a wrong size or empty = none.
  void set_dye(std::span<const float> dye) { has_dye_ = upload_grid_field(dye, dye_tex_); }
  void set_foam(std::span<const float> foam) { has_foam_ = upload_grid_field(foam, foam_tex_); }
  /// The view's linearisation (when the view or the index changed) and the prepared heights.
  void upload(const OrbitCamera& camera, float index);
  /// The surface; `bed` (R32F, m after the offset) is the terrain under it, or null for a flat floor;
  /// its refracted and reflected rays meet the scene's solids (ShadingScene::solids).
  void draw(const FrameContext& f, const ShadingScene& scene, const gl::Texture* bed) const;
  /// The water's sides (seen where no deck hides them: a quasi-2D slab from the side shows its
  /// profile), in the water's colour; where the surface is hidden as dry, so is its side.
  void draw_sides(const FrameContext& f, const FlatDrawer& flat) const;

  /// Water thinner than this is not drawn over a bed, nor over the floor with hide_dry (unit: m).
  static constexpr float kDryDepth = 0.002f;

 private:
  void build_mesh();
  bool upload_grid_field(std::span<const float> values, gl::Texture& tex) const;

  GridPlacement grid_;
  double ground_z_;
  std::size_t factor_;  // the subsampling factor
  SurfaceMeshLayout layout_;
  std::vector<float> mesh_h_, diffs_;
  bool heights_dirty_ = true;
  gl::Program prog_;
  gl::Texture diffs_tex_, coef_tex_, dye_tex_, foam_tex_;
  bool has_dye_ = false, has_foam_ = false;
  GLuint vao_ = 0, static_vbo_ = 0, h_vbo_ = 0, lin_vbo_ = 0, ibo_ = 0;
  GLsizei index_count_ = 0;
  // linearisation cache: recomputed when the view rays or the index change
  bool lin_valid_ = false;
  ViewRays lin_view_;
  float lin_index_ = 0.0f;
};

}  // namespace huygens
