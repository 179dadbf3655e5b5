// Writes Manifold's result mesh as OBJ, for comparing triangle quality with ember's output
// (bench/watertight/measure.py --manifold-quality). Same input handling as
// bench/peers/manifold_runner.mjs (EMB1 files, float32 positions); run with cwd bench/peers.
//   node ../watertight/manifold_dump.mjs A.bin B.bin OP OUT.obj
import { writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { pathToFileURL } from 'node:url';
import { readBin } from '../peers/meshbin.mjs';

// manifold-3d is installed in bench/peers/node_modules: resolve it from the working directory
const require = createRequire(process.cwd() + '/');
const { default: Module } = await import(pathToFileURL(require.resolve('manifold-3d/manifold.js')).href);

const [fa, fb, op, out] = process.argv.slice(2);
const wasm = await Module();
wasm.setup();
const { Manifold, Mesh } = wasm;
const A = readBin(fa), B = readBin(fb);
const a = new Manifold(new Mesh({ numProp: 3, vertProperties: A.vert, triVerts: A.tri }));
const b = new Manifold(new Mesh({ numProp: 3, vertProperties: B.vert, triVerts: B.tri }));
const r = op === 'union' ? a.add(b) : op === 'intersection' ? a.intersect(b) : a.subtract(b);
const m = r.getMesh();
if (r.status() !== 'NoError') throw new Error(`result status ${r.status()}`);
const lines = [];
for (let i = 0; i < m.vertProperties.length; i += m.numProp)
  lines.push(`v ${m.vertProperties[i]} ${m.vertProperties[i + 1]} ${m.vertProperties[i + 2]}`);
for (let t = 0; t < m.triVerts.length; t += 3)
  lines.push(`f ${m.triVerts[t] + 1} ${m.triVerts[t + 1] + 1} ${m.triVerts[t + 2] + 1}`);
writeFileSync(out, lines.join('\n') + '\n');
console.log(JSON.stringify({ triangles: m.triVerts.length / 3 }));
