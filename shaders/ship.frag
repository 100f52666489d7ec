#version 330 core
// Flat-shaded hull or obstacle: the face normal from screen-space derivatives of the position.
in vec3 v_pos;
out vec4 o_color;
uniform vec3 u_sun_dir;
uniform vec3 u_eye;
uniform int u_solid;  // 1: an obstacle (concrete grey), 2: the water's sides, 3: a tank's wall
void main() {
  vec3 n = normalize(cross(dFdx(v_pos), dFdy(v_pos)));
  if (dot(n, u_eye - v_pos) < 0.0) n = -n;
  float lambert = max(dot(n, normalize(u_sun_dir)), 0.0);
  // a hull: the deck (facing up) pale grey fibreglass, the topsides white, below the waterline
  // red antifouling (a wooden deck read as a brown log on the sea from a low view)
  vec3 hull = abs(n.z) > 0.8 ? vec3(0.78, 0.78, 0.76) : v_pos.z > 0.0 ? vec3(0.93, 0.93, 0.91) : vec3(0.55, 0.12, 0.10);
  vec3 base = u_solid == 3 ? vec3(0.86, 0.88, 0.90) : u_solid == 2 ? vec3(0.10, 0.38, 0.48) : u_solid != 0 ? vec3(0.62, 0.60, 0.57) : hull;
  float ambient = u_solid == 3 ? 0.7 : 0.35;  // a tank's walls: pale, a backdrop
  // the colours above are sRGB values: decoded to linear radiance (IEC 61966-2-1)
  base = mix(base / 12.92, pow((base + 0.055) / 1.055, vec3(2.4)), step(vec3(0.04045), base));
  o_color = vec4(base * (ambient + (1.0 - ambient) * lambert), 1.0);
}
