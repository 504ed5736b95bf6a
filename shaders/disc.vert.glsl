#version 330 core
// One instanced quad per particle, big enough for the disc plus one pixel of
// anti-aliasing fringe. Triangles are clipped exactly, so discs whose centre lies
// outside the frame still show their visible part (no popping at the edges).
layout(location = 0) in vec2 corner;  // quad corner in [-1, 1]^2
layout(location = 1) in vec2 center;  // particle centre, world units relative to the view origin
layout(location = 2) in vec3 color;   // normalised RGB

uniform vec2 u_world_to_ndc;  // scale from world units to normalised device coordinates
uniform vec2 u_ndc_offset;
uniform vec2 u_pixel_to_ndc;  // 2 / width, 2 / height
uniform float u_radius_px;    // disc radius in pixels

out vec2 v_offset_px;  // fragment offset from the disc centre in pixels
out vec3 v_color;

void main() {
  float extent = u_radius_px + 1.0;
  v_offset_px = corner * extent;
  vec2 ndc = center * u_world_to_ndc + u_ndc_offset + v_offset_px * u_pixel_to_ndc;
  gl_Position = vec4(ndc, 0.0, 1.0);
  v_color = color;
}
