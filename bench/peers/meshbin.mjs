// Reads the benchmark's binary mesh files (EMB1, bench/compare/meshbin.hpp) into
// float32 positions and uint32 triangles, the arrays manifold-3d takes.
import { readFileSync } from 'node:fs';

export function readBin(path) {
  const buf = readFileSync(path);
  if (buf.toString('latin1', 0, 4) !== 'EMB1') throw new Error(`malformed mesh file ${path}`);
  const nv = Number(buf.readBigUInt64LE(4));
  const nt = Number(buf.readBigUInt64LE(12));
  const xyz = new Float64Array(buf.buffer.slice(buf.byteOffset + 20, buf.byteOffset + 20 + 24 * nv));
  const triStart = buf.byteOffset + 20 + 24 * nv;
  const tri = new Uint32Array(buf.buffer.slice(triStart, triStart + 12 * nt));
  return { vert: Float32Array.from(xyz), tri, nt };
}
