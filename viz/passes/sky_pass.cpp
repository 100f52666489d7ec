#include "sky_pass.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <glm/gtc/type_ptr.hpp>

namespace huygens {

SkyPass::SkyPass() : prog_(load_lit_program("background.vert", "background.frag")) {
  glGenVertexArrays(1, &empty_vao_);
}

SkyPass::~SkyPass() {
  if (sea_sampler_ != 0) glDeleteSamplers(1, &sea_sampler_);
  glDeleteVertexArrays(1, &empty_vao_);
}

void SkyPass::set_ambient_sea(const RenderAmbientSea& sea) {
  sea_ = sea.slopes;
  const int n = sea_->n();
  sea_time_ = std::numeric_limits<double>::quiet_NaN();
  // every level down to 1 x 1: far away a texel averages the slopes (the sea flattens to its mean
  // colour instead of aliasing); anisotropic where the driver offers it (grazing views)
  sea_tex_ = gl::Texture(n, n, GL_RGBA32F, static_cast<int>(std::bit_width(static_cast<unsigned>(n))));
  sea_texels_.assign(4 * static_cast<std::size_t>(n) * n, 0.0f);
  // both unresolved variances are constant in time (each mode's amplitude is)
  const double cox_munk = 0.003 + 5.12e-3 * sea.wind_speed_mps;
  sea_unresolved_var_ = std::max(cox_munk - sea_->mean_square_slope(false), 0.0);
  region_unresolved_var_ = std::max(cox_munk - sea_->mean_square_slope(true), 0.0);
  sea_tex_.set_filter(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR);
  sea_tex_.set_wrap(GL_REPEAT);
  if (epoxy_has_gl_extension("GL_EXT_texture_filter_anisotropic")) {
    GLfloat most = 1.0f;
    glGetFloatv(GL_MAX_TEXTURE_MAX_ANISOTROPY_EXT, &most);
    glBindTexture(GL_TEXTURE_2D, sea_tex_.id());
    glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_MAX_ANISOTROPY_EXT, std::min(most, 16.0f));
  }
  // the sea out to the horizon samples the slopes without anisotropic filtering: at its
  // footprints llvmpipe's took 1.4 s for a 1280x720 frame
  if (sea_sampler_ == 0) glGenSamplers(1, &sea_sampler_);
  glSamplerParameteri(sea_sampler_, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glSamplerParameteri(sea_sampler_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glSamplerParameteri(sea_sampler_, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glSamplerParameteri(sea_sampler_, GL_TEXTURE_WRAP_T, GL_REPEAT);
  set_sea_time(0.0);
}

void SkyPass::update(const RenderSettings& s) {
  const double t = sea_request_;
  if (!sea_ || !s.deep_water || !s.ambient_sea || t == sea_time_ || !std::isfinite(t)) return;
  // the squares' sum too: the mipmap's averages of it give the slopes' variance in a texel
  const std::span<const float> slopes = sea_->compute(t);
  for (std::size_t i = 0; i < slopes.size() / 2; ++i) {
    const float sx = slopes[2 * i], sy = slopes[2 * i + 1];
    sea_texels_[4 * i] = sx, sea_texels_[4 * i + 1] = sy, sea_texels_[4 * i + 2] = sx * sx + sy * sy;
  }
  sea_tex_.upload(sea_texels_.data(), GL_RGBA, GL_FLOAT, 0);
  glBindTexture(GL_TEXTURE_2D, sea_tex_.id());
  glGenerateMipmap(GL_TEXTURE_2D);
  sea_time_ = t;
}

std::optional<ShadingScene::FarSea> SkyPass::far_sea(const RenderSettings& s) const {
  if (!sea_ || !s.deep_water || !s.ambient_sea) return std::nullopt;
  return ShadingScene::FarSea{&sea_tex_, sea_->length_m(), sea_->n(), sea_unresolved_var_, region_unresolved_var_};
}

void SkyPass::draw(const FrameContext& f, const ShadingScene& scene) const {
  set_shading_uniforms(prog_, f, scene);
  glUniformMatrix4fv(prog_.loc("u_inv_vp"), 1, GL_FALSE, glm::value_ptr(glm::inverse(f.mvp)));
  glBindSampler(7, sea_sampler_);  // 0 (the texture's own) without an ambient sea
  glDepthFunc(GL_LEQUAL);
  glBindVertexArray(empty_vao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDepthFunc(GL_LESS);
  glBindSampler(7, 0);
}

}  // namespace huygens
