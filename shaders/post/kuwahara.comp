#version 450 core
// Kuwahara (WWDC 2003 session 212) in one compute pass with shared-memory tiles (issue 37): a 16×16
// group loads the texels its pixels' quadrants cover once, sums each quadrant-sized block
// once — rows of s, then columns of s rows — and every pixel keeps the mean of the calmest
// of its four blocks. Nothing goes through a statistics texture; the fragment version
// (kuwahara_stats.frag, then kuwahara_select.frag) is kept for the bench's comparison.
//
// The same integers as image/post.h's reference: k = round(255·value) per channel, a
// block's Σk and D = n·Σ_c Σk_c² − Σ_c (Σk_c)² (n = s², s ≤ 8: D < 2³¹), compared exactly
// (the two-pass version compares D rounded to a float above s = 4). Ties go to the lowest
// quadrant number: 0 upper-left, 1 upper-right, 2 lower-left, 3 lower-right.
//
// Shared memory, sized for s = 8 (A = s − 1 = 7): the input tile, 30×30 texels' k (10.8 KB);
// row sums of s texels, 30 rows × 23 blocks, Σk and Σ_c k² (11 KB); the 23×23 blocks' Σk
// and D (8.5 KB): 30.3 KB of the 32 KB every GL 4.3 implementation gives a group.
#include "post/common.glsl"
#include "post/compute_output.glsl"

uniform sampler2D uInput;
uniform int uSize;
uniform bool uShowQuadrant;

const int kTile = 16;
const int kMaxApron = 7;
const int kMaxInput = kTile + 2 * kMaxApron;  // 30
const int kMaxBlocks = kTile + kMaxApron;     // 23

// k per channel as three int arrays (an ivec3 array may be padded to 16 bytes an element).
shared int sRed[kMaxInput * kMaxInput], sGreen[kMaxInput * kMaxInput], sBlue[kMaxInput * kMaxInput];
shared ivec4 sRow[kMaxInput * kMaxBlocks];     // xyz: Σk over s texels of a row; w: Σ_c Σk²
shared ivec4 sBlock[kMaxBlocks * kMaxBlocks];  // xyz: Σk over the block; w: D

void main() {
  const int s = uSize, apron = s - 1, inputs = kTile + 2 * apron, blocks = kTile + apron;
  const int thread = int(gl_LocalInvocationIndex), threads = kTile * kTile;
  // Local (0, 0) of the input tile and of the blocks' top-left corners is this global texel.
  const ivec2 origin = ivec2(gl_WorkGroupID.xy) * kTile - apron;

  for (int i = thread; i < inputs * inputs; i += threads) {
    ivec2 local = ivec2(i % inputs, i / inputs);
    ivec3 k = ivec3(round(fetchClamped(uInput, origin + local).rgb * 255.0));
    int at = local.y * kMaxInput + local.x;
    sRed[at] = k.r;
    sGreen[at] = k.g;
    sBlue[at] = k.b;
  }
  barrier();

  // Row sums: for each input row, the s texels starting at each block column.
  for (int i = thread; i < inputs * blocks; i += threads) {
    int row = i / blocks, column = i % blocks;
    ivec3 sum = ivec3(0), squares = ivec3(0);
    for (int k = 0; k < s; ++k) {
      int at = row * kMaxInput + column + k;
      ivec3 texel = ivec3(sRed[at], sGreen[at], sBlue[at]);
      sum += texel;
      squares += texel * texel;
    }
    sRow[row * kMaxBlocks + column] = ivec4(sum, squares.r + squares.g + squares.b);
  }
  barrier();

  // Blocks: s row sums down each column.
  for (int i = thread; i < blocks * blocks; i += threads) {
    int row = i / blocks, column = i % blocks;
    ivec4 total = ivec4(0);
    for (int k = 0; k < s; ++k) total += sRow[(row + k) * kMaxBlocks + column];
    ivec3 sum = total.xyz;
    sBlock[row * kMaxBlocks + column] = ivec4(sum, s * s * total.w - (sum.r * sum.r + sum.g * sum.g + sum.b * sum.b));
  }
  barrier();

  ivec2 p;
  if (!outputTexel(p)) return;
  // Pixel p's quadrants have their top-left corners at p − (A, A), p − (0, A), p − (A, 0)
  // and p: blocks l, l + (A, 0), l + (0, A), l + (A, A) of the tile.
  ivec2 l = ivec2(gl_LocalInvocationID.xy);
  ivec4 best = sBlock[l.y * kMaxBlocks + l.x];
  int chosen = 0;
  ivec4 q1 = sBlock[l.y * kMaxBlocks + l.x + apron];
  ivec4 q2 = sBlock[(l.y + apron) * kMaxBlocks + l.x];
  ivec4 q3 = sBlock[(l.y + apron) * kMaxBlocks + l.x + apron];
  if (q1.w < best.w) { best = q1; chosen = 1; }
  if (q2.w < best.w) { best = q2; chosen = 2; }
  if (q3.w < best.w) { best = q3; chosen = 3; }
  float alpha = texelFetch(uInput, p, 0).a;
  if (uShowQuadrant) {
    imageStore(uTarget, p, vec4(vec3(float(chosen) / 255.0), alpha));
  } else {
    imageStore(uTarget, p, vec4(vec3(best.xyz) / (float(s * s) * 255.0), alpha));
  }
}
