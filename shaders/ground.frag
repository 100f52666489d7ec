// (#version and ground_common.glsl are prepended by the renderer)
// The ground seen directly (no water in between).
in vec2 v_xy;
out vec4 o_color;
void main() { o_color = vec4(lit_ground(v_xy), 1.0); }
