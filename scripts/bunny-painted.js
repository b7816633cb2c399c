#!/usr/bin/env node
// Derives a "painted" Stanford bunny from data/bunny/bunny.ply for the every-map picture
// of docs/bake.md (scripts/bake-sheet runs it): the same surface with three named
// materials by region and a colour per vertex, plus the card (an impostor facing +Z)
// and its cage that the bunny is baked onto.
//
//   node scripts/bunny-painted.js <bunny.ply> <out dir>
//
// Writes into <out dir>:
//   bunny_painted.obj, bunny_painted.mtl  the high poly: `v x y z r g b`, `vn` (smooth,
//       area-weighted normals of the scan), `usemtl body|ears|footpads`. The triangles that
//       straddle a region border are cut along it (the cut points shared by both sides,
//       so the mesh stays watertight), so each material ends on a smooth line, not on
//       the scan's jagged triangle edges. ears: above the plane
//       y = max(7.01, 6.45 - 0.43 x) (the ears stand above the head, which faces -X);
//       footpads: y < 1.01 (the soles and the base); body: the rest. (Names whose colours in
//       --material-id, a hash of the name, are far apart: red, green, blue.)
//       Vertex colour: a bilinear blend of four colours over the bunny's x/y extent
//       (nose-bottom orange, nose-top magenta, tail-bottom green, tail-top blue),
//       smooth everywhere and unrelated to the material regions.
//   card.obj, card_cage.obj  a square (two triangles, UVs 0..1 with u along +X and v
//       along +Y, normal +Z) around the bunny's x/y extent at z = 0, and the same
//       square at z = 4.5 (the cage: rays go from it towards the card and 4.5 behind).
//
// Deterministic: the same input gives the same bytes.
'use strict';
const fs = require('fs');
const path = require('path');

const [input, outDir] = process.argv.slice(2);
if (!input || !outDir) {
  console.error('usage: bunny-painted.js <bunny.ply> <out dir>');
  process.exit(2);
}

// --- read the ASCII PLY that scripts/bunny-to-ply.js writes (x y z, then triangles) ---
const lines = fs.readFileSync(input, 'utf8').split('\n');
let nv = -1, nf = -1, at = 0;
if (lines[0].trim() !== 'ply' || !lines[1].startsWith('format ascii')) {
  console.error(`${input}: not an ASCII PLY file`);
  process.exit(3);
}
for (; at < lines.length; ++at) {
  const l = lines[at].trim();
  if (l.startsWith('element vertex')) nv = +l.split(/\s+/)[2];
  if (l.startsWith('element face')) nf = +l.split(/\s+/)[2];
  if (l === 'end_header') { ++at; break; }
}
if (!(nv > 0 && nf > 0)) {
  console.error(`${input}: no vertex or face count in the header`);
  process.exit(3);
}
const P = [];   // positions [x, y, z]
for (let i = 0; i < nv; ++i) P.push(lines[at + i].trim().split(/\s+/).slice(0, 3).map(Number));
let T = [];     // triangles [a, b, c]
for (let i = 0; i < nf; ++i) {
  const f = lines[at + nv + i].trim().split(/\s+/).map(Number);
  if (f[0] !== 3) { console.error(`${input}: face ${i} is not a triangle`); process.exit(3); }
  T.push([f[1], f[2], f[3]]);
}

const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const normalize = (a) => { const l = Math.hypot(a[0], a[1], a[2]) || 1; return [a[0] / l, a[1] / l, a[2] / l]; };
const lerp = (a, b, t) => a.map((x, k) => x + (b[k] - x) * t);

// --- smooth normals of the scan (area-weighted), interpolated at the cut points later ---
const N = P.map(() => [0, 0, 0]);
for (const [a, b, c] of T) {
  const n = cross(sub(P[b], P[a]), sub(P[c], P[a]));  // length = twice the area
  for (const v of [a, b, c]) for (let k = 0; k < 3; ++k) N[v][k] += n[k];
}
for (let i = 0; i < N.length; ++i) N[i] = normalize(N[i]);

// --- cut every triangle that straddles a plane dot(n, p) = d ---
// A point on an edge is made once (keyed by the edge), so both triangles of the edge share it.
function cutBy(n, d) {
  const f = (i) => n[0] * P[i][0] + n[1] * P[i][1] + n[2] * P[i][2] - d;
  const cache = new Map();
  const edgePoint = (i, j) => {
    const key = i < j ? `${i},${j}` : `${j},${i}`;
    if (cache.has(key)) return cache.get(key);
    const [lo, hi] = i < j ? [i, j] : [j, i];  // the same point whichever way the edge runs
    const t = f(lo) / (f(lo) - f(hi));
    P.push(lerp(P[lo], P[hi], t));
    N.push(normalize(lerp(N[lo], N[hi], t)));
    cache.set(key, P.length - 1);
    return P.length - 1;
  };
  const out = [];
  for (const tri of T) {
    const s = tri.map((v) => f(v) >= 0);
    if (s[0] === s[1] && s[1] === s[2]) { out.push(tri); continue; }
    // Rotate so that vertex 0 is the one alone on its side (keeps the winding).
    let r = 0;
    while (!(s[r] !== s[(r + 1) % 3] && s[r] !== s[(r + 2) % 3])) ++r;
    const a = tri[r], b = tri[(r + 1) % 3], c = tri[(r + 2) % 3];
    const ab = edgePoint(a, b), ac = edgePoint(a, c);
    out.push([a, ab, ac], [ab, b, c], [ab, c, ac]);
  }
  T = out;
}
// The constants end in .01 so that no scan vertex lies on a plane.
cutBy([0, 1, 0], 7.01);          // ears: above y = 7.01 ...
cutBy([0.43, 1, 0], 6.45);       // ... and above y = 6.45 - 0.43 x
cutBy([0, 1, 0], 1.01);          // footpads: below y = 1.01

const region = (p) => {
  if (p[1] > 7.01 && p[1] + 0.43 * p[0] > 6.45) return 'ears';
  if (p[1] < 1.01) return 'footpads';
  return 'body';
};

// --- bounds, vertex colours ---
const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
for (const p of P) for (let k = 0; k < 3; ++k) { lo[k] = Math.min(lo[k], p[k]); hi[k] = Math.max(hi[k], p[k]); }
const corner = { noseLow: [0.95, 0.55, 0.10], noseHigh: [0.85, 0.20, 0.60],
                 tailLow: [0.20, 0.75, 0.30], tailHigh: [0.15, 0.35, 0.90] };
const colour = (p) => {
  const u = (p[0] - lo[0]) / (hi[0] - lo[0]), v = (p[1] - lo[1]) / (hi[1] - lo[1]);
  return lerp(lerp(corner.noseLow, corner.tailLow, u), lerp(corner.noseHigh, corner.tailHigh, u), v);
};

// --- the high poly: OBJ + MTL, faces grouped by material ---
const materials = ['body', 'ears', 'footpads'];
const byMaterial = new Map(materials.map((m) => [m, []]));
for (const tri of T) {
  const c = lerp(lerp(P[tri[0]], P[tri[1]], 0.5), P[tri[2]], 1 / 3);  // centroid
  byMaterial.get(region(c)).push(tri);
}
const f6 = (x) => x.toFixed(6);
const obj = ['# The Stanford bunny painted by scripts/bunny-painted.js: three materials by region,',
             '# a colour per vertex (v x y z r g b), smooth normals.', 'mtllib bunny_painted.mtl'];
for (let i = 0; i < P.length; ++i) obj.push(`v ${P[i].map(f6).join(' ')} ${colour(P[i]).map(f6).join(' ')}`);
for (const n of N) obj.push(`vn ${n.map(f6).join(' ')}`);
for (const m of materials) {
  obj.push(`g ${m}`, `usemtl ${m}`);
  for (const tri of byMaterial.get(m)) obj.push(`f ${tri.map((v) => `${v + 1}//${v + 1}`).join(' ')}`);
}
const mtl = ['# Materials of bunny_painted.obj (glint bake --material-id colours them by name).',
             'newmtl body', 'Kd 0.60 0.50 0.40', '', 'newmtl ears', 'Kd 0.90 0.70 0.70', '',
             'newmtl footpads', 'Kd 0.30 0.25 0.20'];

// --- the card and its cage ---
if (Math.max(-lo[2], hi[2]) >= 4.5) {
  console.error(`${input}: the bunny reaches |z| = ${Math.max(-lo[2], hi[2])}, past the cage at 4.5`);
  process.exit(3);
}
const cx = (lo[0] + hi[0]) / 2, cy = (lo[1] + hi[1]) / 2;
const half = 0.55 * Math.max(hi[0] - lo[0], hi[1] - lo[1]);
const card = (z) => ['# A square facing +Z around the bunny (scripts/bunny-painted.js).',
  ...[[-1, -1], [1, -1], [1, 1], [-1, 1]].map(([sx, sy]) => `v ${f6(cx + sx * half)} ${f6(cy + sy * half)} ${f6(z)}`),
  'vt 0 0', 'vt 1 0', 'vt 1 1', 'vt 0 1', 'vn 0 0 1', 'f 1/1/1 2/2/1 3/3/1', 'f 1/1/1 3/3/1 4/4/1'];

fs.mkdirSync(outDir, { recursive: true });
const write = (name, text) => {  // via a temporary name, so an interrupted run leaves no half file
  const file = path.join(outDir, name);
  fs.writeFileSync(file + '.tmp', text.join('\n') + '\n');
  fs.renameSync(file + '.tmp', file);
};
write('bunny_painted.obj', obj);
write('bunny_painted.mtl', mtl);
write('card.obj', card(0));
write('card_cage.obj', card(4.5));
console.log(`bunny_painted.obj: ${P.length} vertices, ${T.length} triangles ` +
            `(${materials.map((m) => `${m} ${byMaterial.get(m).length}`).join(', ')}); card ${f6(2 * half)} wide`);
