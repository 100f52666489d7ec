#pragma once
// The ground pass (docs/viz.md "Ground"): the floor seen directly (tiles, a checker or a uniform
// colour, lit by ambient + sun x caustics), the pool's deck at the rest level around the visible
// region, or the bed as terrain lit with its slope (shaders/ground.vert, ground.frag). It also owns
// the floor's pattern texture and the bed's height texture, which the surface pass samples.
#include <span>
#include <vector>

#include "gl.hpp"
#include "refraction.hpp"
#include "shading.hpp"

namespace huygens {

class GroundPass {
 public:
  GroundPass(const GridPlacement& grid, double ground_z, const SurfaceMeshLayout& layout);
  ~GroundPass();
  GroundPass(const GroundPass&) = delete;
  GroundPass& operator=(const GroundPass&) = delete;

  /// The floor tiles' side (GroundPattern::tiles; unit: m): the 1-2-5 length nearest an eighth of
  /// the visible region's longer side, the tiles square and aligned with the frame's origin.
  double tile_m() const;
  /// The bed (rows x cols, m, already lowered by the height offset): the terrain mesh (the surface
  /// mesh's points at the bed's height) and the bed texture. Empty or a wrong size = a flat floor.
  void set_bed(std::span<const float> bed);
  /// The bed's heights (R32F, m) when there is one, else null.
  const gl::Texture* bed() const { return has_bed_ ? &bed_tex_ : nullptr; }
  /// The floor's pattern texture for these settings (made again only when the pattern changed),
  /// bound to texture unit 0 by bind_pattern.
  void update_pattern(const RenderSettings& s);
  void bind_pattern() const { pattern_tex_.bind(0); }
  /// The terrain (with the deck ending at the outline), or the floor and the deck; deep water has
  /// no floor, only the deck (the sea around the region).
  void draw(const FrameContext& f, const ShadingScene& scene) const;

 private:
  void build_quads();
  void draw_terrain(const FrameContext& f, const ShadingScene& scene) const;
  void draw_floor(const FrameContext& f, const ShadingScene& scene) const;

  GridPlacement grid_;
  double ground_z_;
  SurfaceMeshLayout layout_;
  gl::Program prog_;
  gl::Texture pattern_tex_, bed_tex_;
  int pattern_key_ = -1;
  bool has_bed_ = false;
  GLuint quads_vao_ = 0, quads_vbo_ = 0;
  GLuint terrain_vao_ = 0, terrain_vbo_ = 0, terrain_ibo_ = 0;
  GLsizei terrain_index_count_ = 0;
};

}  // namespace huygens
