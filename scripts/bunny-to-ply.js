#!/usr/bin/env node
// Converts the npm package `bunny` (the Stanford bunny as {positions, cells}) into an
// ASCII PLY file glint loads with Assimp. Used by scripts/setup.
//
//   node scripts/bunny-to-ply.js <node_modules dir> <out.ply>
//
// The mesh is written as it is (about 2.5k vertices, 4.97k triangles, with the
// scanner's holes in the base): glint's shadow volumes must cope with the holes.
'use strict';
const fs = require('fs');
const path = require('path');

const [modules, out] = process.argv.slice(2);
if (!modules || !out) {
  console.error('usage: bunny-to-ply.js <node_modules dir> <out.ply>');
  process.exit(2);
}
const bunny = require(path.resolve(modules, 'bunny'));
const lines = [
  'ply',
  'format ascii 1.0',
  'comment Stanford bunny from the npm package "bunny" (Stanford 3D Scanning Repository)',
  `element vertex ${bunny.positions.length}`,
  'property float x',
  'property float y',
  'property float z',
  `element face ${bunny.cells.length}`,
  'property list uchar int vertex_indices',
  'end_header',
];
for (const p of bunny.positions) lines.push(p.join(' '));
for (const c of bunny.cells) lines.push(`${c.length} ${c.join(' ')}`);
// Write to a temporary name and rename, so an interrupted run never leaves half a file.
fs.writeFileSync(out + '.tmp', lines.join('\n') + '\n');
fs.renameSync(out + '.tmp', out);
console.log(`bunny: ${bunny.positions.length} vertices, ${bunny.cells.length} triangles -> ${out}`);
