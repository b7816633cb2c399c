#pragma once
// glint/image/heightfield.h — procedural height fields and matching colour textures for the
// bump-mapping demos, so glint ships no binary textures.
//
// Contents
//   BrickOptions      layout of a brick wall
//   makeBrickHeight   one-channel float heights: bevelled bricks, recessed mortar, pitted surface
//   makeBrickAlbedo   RGBA8 colours of the same wall (brick to brick variation, grey mortar)
//   makeBumpsHeight   round bumps and dents on a grid: the clearest test of a lighting sign
//
// Every image tiles seamlessly (use NormalMapOptions::wrap = true when making its normal
// map) and is deterministic (hash-based noise, no global random state). Row 0 is the top.

#include "glint/core/math.h"
#include "glint/image/image.h"

namespace glint {

struct BrickOptions {
  int rows = 8;              ///< brick courses per tile (alternate courses offset by half a brick)
  int bricksPerRow = 4;      ///< bricks per course
  float mortar = 0.035f;     ///< mortar joint width, fraction of the tile
  float bevel = 0.03f;       ///< width of the rounded brick edge, fraction of the tile
  float roughness = 0.06f;   ///< amplitude of the pitted surface noise (height units)
  unsigned seed = 7;         ///< varies the noise and brick colours
};

/// size × size heights in [0, 1]: mortar at 0.1, brick faces about 0.9.
Image makeBrickHeight(int size, const BrickOptions& options = {});
/// size × size colours of the same layout.
Image makeBrickAlbedo(int size, const BrickOptions& options = {});
/// size × size RGBA8 pool tiles: `tiles` × `tiles` pale aqua tiles with darker grout lines,
/// a little tile-to-tile variation (the floor seen through the water scenes).
Image makePoolTiles(int size, int tiles = 8);
/// size × size heights: `count` × `count` cells, each holding a round bump (even cells) or a
/// dent (odd cells) of smooth cosine profile; 0.5 between them.
Image makeBumpsHeight(int size, int count = 4);

}  // namespace glint
