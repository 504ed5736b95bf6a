#version 330 core
// Anti-aliased disc: coverage falls from 1 to 0 over one pixel at the rim.
in vec2 v_offset_px;
in vec3 v_color;
uniform float u_radius_px;
out vec4 frag_color;

void main() {
  float coverage = clamp(u_radius_px - length(v_offset_px) + 0.5, 0.0, 1.0);
  if (coverage <= 0.0) discard;
  frag_color = vec4(v_color, coverage);
}
