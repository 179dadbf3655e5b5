// Manifold peer of the comparison benchmark; driven by bench/compare/bench.py.
//
//   node manifold_runner.mjs A.bin B.bin [--ops ..] [--runs R] [--budget-ms B] [--warmup W]
//
// Uses the manifold-3d WASM build from the npm registry (single-threaded).
// Reading the binary files (bench/compare/meshbin.hpp) and converting them to
// Float32Array/Uint32Array is untimed; every timed run builds both Mesh and
// Manifold objects from those arrays, performs the Boolean and reads the result
// back with getMesh() (Manifold evaluates lazily, so getMesh is where the work
// happens). Failures (constructor errors, non-OK status) are recorded per
// operation. Output: one JSON line per operation, like the C++ runners.
import { performance } from 'node:perf_hooks';
import Module from 'manifold-3d';
import { readBin } from './meshbin.mjs';

function signedVolume(vert, tri, numProp) {
  let vol = 0;
  for (let t = 0; t < tri.length; t += 3) {
    const a = tri[t] * numProp, b = tri[t + 1] * numProp, c = tri[t + 2] * numProp;
    const ax = vert[a], ay = vert[a + 1], az = vert[a + 2];
    const bx = vert[b], by = vert[b + 1], bz = vert[b + 2];
    const cx = vert[c], cy = vert[c + 1], cz = vert[c + 2];
    vol += ax * (by * cz - bz * cy) + ay * (bz * cx - bx * cz) + az * (bx * cy - by * cx);
  }
  return vol / 6;
}

const argv = process.argv.slice(2);
const pos = [];
let ops = ['union', 'intersection', 'difference'];
let runs = 5;
let budget = Infinity;
let warmup = 0; // untimed runs first; the first one is reported as cold_ms (runner_common.hpp)
for (let i = 0; i < argv.length; ++i) {
  if (argv[i] === '--ops') ops = argv[++i].split(',').filter((s) => s);
  else if (argv[i] === '--runs') runs = Math.max(1, parseInt(argv[++i], 10));
  else if (argv[i] === '--budget-ms') budget = parseFloat(argv[++i]);
  else if (argv[i] === '--warmup') warmup = Math.max(0, parseInt(argv[++i], 10));
  else if (argv[i] === '--threads') ++i;
  else pos.push(argv[i]);
}
if (pos.length !== 2) {
  console.error('usage: node manifold_runner.mjs A.bin B.bin [--ops ..] [--runs R] [--budget-ms B] [--warmup W]');
  process.exit(2);
}

const wasm = await Module();
wasm.setup();
const { Manifold, Mesh } = wasm;
const A = readBin(pos[0]);
const B = readBin(pos[1]);

function once(op) {
  const objs = [];
  try {
    const ma = new Mesh({ numProp: 3, vertProperties: A.vert, triVerts: A.tri });
    const mb = new Mesh({ numProp: 3, vertProperties: B.vert, triVerts: B.tri });
    const a = new Manifold(ma);
    objs.push(a);
    const b = new Manifold(mb);
    objs.push(b);
    if (a.status() !== 'NoError') throw new Error(`input A rejected: ${a.status()}`);
    if (b.status() !== 'NoError') throw new Error(`input B rejected: ${b.status()}`);
    const r = op === 'union' ? a.add(b) : op === 'intersection' ? a.intersect(b) : op === 'difference' ? a.subtract(b) : null;
    if (!r) throw new Error(`unknown op ${op}`);
    objs.push(r);
    const out = r.getMesh();
    if (r.status() !== 'NoError') throw new Error(`result status ${r.status()}`);
    return { vert: out.vertProperties, tri: out.triVerts, numProp: out.numProp };
  } finally {
    for (const o of objs) o.delete();
  }
}

for (const op of ops) {
  const times = [];
  let last = null;
  let error = '';
  let total = 0;
  let coldMs = null;
  for (let r = 0; r < warmup + runs; ++r) {
    const t0 = performance.now();
    try {
      last = once(op);
    } catch (e) {
      error = `exception: ${e && e.message ? e.message : String(e)}`;
      last = null;
      break;
    }
    const ms = performance.now() - t0;
    if (r < warmup) {
      if (r === 0) coldMs = ms;
      continue;
    }
    times.push(ms);
    total += ms;
    if (total >= budget) break;
  }
  const ok = last !== null;
  const sorted = [...times].sort((x, y) => x - y);
  const n = sorted.length;
  const median = n === 0 ? null : n % 2 ? sorted[(n - 1) / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
  const line = {
    tool: 'manifold', op, threads: 1, ok, runs: ok ? times.length : 0,
    median_ms: ok ? median : null, times_ms: ok ? times : [], cold_ms: ok ? coldMs : null,
    out_polygons: ok ? last.tri.length / 3 : 0,
    out_volume: ok ? signedVolume(last.vert, last.tri, last.numProp) : null,
    in_triangles: A.nt + B.nt,
    peak_rss_kib: Math.round(process.resourceUsage().maxRSS),
    error,
  };
  process.stdout.write(JSON.stringify(line) + '\n');
}
