// What every post pass shares: the luma weights and the border rule (image/post.h).

// YIQ's Y = BT.601 luma, on stored (gamma-encoded) values: image/post.h's kLuma*.
const vec3 kLuma = vec3(0.299, 0.587, 0.114);

// The texel at integer coordinates p, with neighbours outside the image repeating the
// nearest edge texel (clamp to edge, OpenCV's BORDER_REPLICATE). texelFetch ignores the
// sampler, so filtering and wrap modes of the texture do not matter.
vec4 fetchClamped(sampler2D image, ivec2 p) {
  return texelFetch(image, clamp(p, ivec2(0), textureSize(image, 0) - 1), 0);
}

float lumaAt(sampler2D image, ivec2 p) { return dot(fetchClamped(image, p).rgb, kLuma); }

// (Gx, Gy) of the luma: WWDC 2003 session 212's eight fetches around p, kernels as in image/post.h
// (x to the right, y DOWN the picture: texel row 0 is the top row).
vec2 sobel(sampler2D image, ivec2 p) {
  float tl = lumaAt(image, p + ivec2(-1, -1)), t = lumaAt(image, p + ivec2(0, -1)), tr = lumaAt(image, p + ivec2(1, -1));
  float l = lumaAt(image, p + ivec2(-1, 0)), r = lumaAt(image, p + ivec2(1, 0));
  float bl = lumaAt(image, p + ivec2(-1, 1)), b = lumaAt(image, p + ivec2(0, 1)), br = lumaAt(image, p + ivec2(1, 1));
  float gx = (tr + 2.0 * r + br) - (tl + 2.0 * l + bl);
  float gy = (bl + 2.0 * b + br) - (tl + 2.0 * t + tr);
  return vec2(gx, gy);
}
