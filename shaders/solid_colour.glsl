// The colour of a solid's surface at p (world, m) with the unit normal n turned towards the viewer,
// lit from the unit direction `light` (towards the sun; under the water the sun's refracted ray),
// linear radiance. Shared by ship.frag (the solids drawn) and solids_optics.glsl (the solids seen in
// and through the water), so both show the same solid. kind: 0 a hull, 1 an obstacle (concrete
// grey), 2 the water's sides, 3 a tank's wall.
vec3 solid_colour(vec3 p, vec3 n, int kind, vec3 light) {
  float lambert = max(dot(n, light), 0.0);
  // a hull: the deck (facing up) pale grey fibreglass, the topsides white, below the waterline
  // red antifouling (a wooden deck read as a brown log on the sea from a low view)
  vec3 hull = abs(n.z) > 0.8 ? vec3(0.78, 0.78, 0.76) : p.z > 0.0 ? vec3(0.93, 0.93, 0.91) : vec3(0.55, 0.12, 0.10);
  vec3 base = kind == 3 ? vec3(0.86, 0.88, 0.90) : kind == 2 ? vec3(0.10, 0.38, 0.48) : kind != 0 ? vec3(0.62, 0.60, 0.57) : hull;
  float ambient = kind == 3 ? 0.7 : 0.35;  // a tank's walls: pale, a backdrop
  // the colours above are sRGB values: decoded to linear radiance (IEC 61966-2-1)
  base = mix(base / 12.92, pow((base + 0.055) / 1.055, vec3(2.4)), step(vec3(0.04045), base));
  return base * (ambient + (1.0 - ambient) * lambert);
}
