#pragma once
// Paper 000's virtual eye points (section 2.1): an obstacle crossing the water is reflected and
// refracted by drawing it into an environment map from a virtual eye, one per object, which the
// surface reads with its per-pixel reflected and refracted directions. No GL: the geometry of the
// method (the renderer's VirtualEyeMaps draws and reads the maps).
//
// With the plane z = h approximating the water round the object (normal up), the eye E:
//   reflection (eq. 1):  E_refl = E - 2 <E - p_plane, n> n, every reflected ray's focus;
//   refraction (eq. 2):  E_refr = a - |E - a| v_refr / |v_refr|, a the point of the object on the
//     plane nearest the eye, v_refr the view ray E -> a refracted at the plane (Snell, eq. 3):
//     the refracted rays have no focus; E_refr is exact for the ray through a only;
//   size (Fig. 3): a deeper point b of the object (below a at the object's bottom) is drawn in the
//     map at the direction of b - E_refr, but seen in reality along the refracted ray t_b of the
//     surface point whose refracted ray meets b; the map is scaled about a's image by
//     k = |uv(b) - uv(a)| / |uv(t_b) - uv(a)| so that b shows where reality has it.
#include <glm/glm.hpp>

namespace huygens {

/// Eq. 1: the eye mirrored in the plane z = h.
glm::dvec3 reflected_eye(const glm::dvec3& eye, double h);

/// The point a of paper 000 section 2.1: where the line from the eye's foot on the plane z = h to
/// the object's axis (the vertical through the middle of its bounding box lo-hi) enters the box's
/// footprint (the axis point itself when the foot is inside it).
glm::dvec3 nearest_waterline_point(const glm::dvec3& eye, const glm::dvec3& lo, const glm::dvec3& hi, double h);

/// Eq. 2: the virtual refracted eye for the point a on the plane z = h (index: water over air).
glm::dvec3 refracted_eye(const glm::dvec3& eye, const glm::dvec3& a, double index);

/// The surface point on the plane z = h whose refracted view ray passes through b (below the plane),
/// found by bisection on the segment from b's foot to the eye's foot; the refracted direction there.
glm::dvec3 refracted_ray_through(const glm::dvec3& eye, const glm::dvec3& b, double h, double index);

}  // namespace huygens
