// (#version and ground_common.glsl are prepended by the renderer)
// The ground seen directly (no water in between): the floor, or the pool deck around the water
// (pale stone, lit by the sun without caustics).
in vec2 v_xy;
in float v_deck;
out vec4 o_color;
void main() {
  if (v_deck > 0.5)
    o_color = vec4(deck_colour(v_xy), 1.0);
  else
    o_color = vec4(lit_ground(v_xy), 1.0);
}
