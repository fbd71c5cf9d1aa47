// What the engine tests (three_frames_test.mjs, cmgen_frames_test.mjs, three_loaders_test.mjs) share:
// test images written as Radiance .hdr files (the format irrmap, three.js's HDRLoader and cmgen all
// read), irrmap run on them, and a small check helper.
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

// A float RGB image, rows from the top.
export class FloatImage {
  constructor(width, height, fill = [0, 0, 0]) {
    this.width = width;
    this.height = height;
    this.data = new Float32Array(width * height * 3);
    for (let i = 0; i < width * height; i++) this.data.set(fill, 3 * i);
  }
  set(x, y, rgb) { this.data.set(rgb, 3 * (y * this.width + x)); }
  get(x, y) { const i = 3 * (y * this.width + x); return [this.data[i], this.data[i + 1], this.data[i + 2]]; }
}

// Radiance RGBE of one pixel (Greg Ward's float2rgbe).
function rgbe([r, g, b]) {
  const v = Math.max(r, g, b);
  if (v < 1e-32) return [0, 0, 0, 0];
  let e = Math.ceil(Math.log2(v));
  if (v / 2 ** e >= 1) e += 1;  // mantissa in [0.5, 1)
  const scale = 256 / 2 ** e;
  return [Math.floor(r * scale), Math.floor(g * scale), Math.floor(b * scale), e + 128];
}

// Writes `image` as an RLE .hdr ("-Y H +X W": the first row stored is the top): each scanline as four
// channel runs of literal chunks, the layout every reader here takes (cmgen's reads no flat scanlines).
export function writeHdr(file, image) {
  if (image.width < 8 || image.width > 0x7fff) throw new Error(`${file}: width ${image.width} cannot be RLE-coded`);
  const chunks = [Buffer.from(`#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y ${image.height} +X ${image.width}\n`)];
  const channel = new Uint8Array(image.width);
  for (let y = 0; y < image.height; y++) {
    const pixels = [];
    for (let x = 0; x < image.width; x++) pixels.push(rgbe(image.get(x, y)));
    const line = [2, 2, image.width >> 8, image.width & 0xff];
    for (let c = 0; c < 4; c++) {
      for (let x = 0; x < image.width; x++) channel[x] = pixels[x][c];
      for (let start = 0; start < image.width; start += 128) {
        const count = Math.min(128, image.width - start);
        line.push(count, ...channel.subarray(start, start + count));
      }
    }
    chunks.push(Buffer.from(line));
  }
  fs.writeFileSync(file, Buffer.concat(chunks));
}

// A horizontal cross (4N x 3N) of six N x N faces given in +x -x +y -y +z -z order, each with rows
// from the top as the Direct3D/OpenGL face table draws them.
export function horizontalCross(faces, n) {
  const cells = [[2, 1], [0, 1], [1, 0], [1, 2], [1, 1], [3, 1]];  // (column, row) of +x -x +y -y +z -z
  const cross = new FloatImage(4 * n, 3 * n);
  faces.forEach((face, f) => {
    for (let y = 0; y < n; y++) for (let x = 0; x < n; x++) cross.set(cells[f][0] * n + x, cells[f][1] * n + y, face.get(x, y));
  });
  return cross;
}

// Runs `irrmap INPUT ARGS... --out DIR` and returns DIR.
export function runIrrmap(irrmap, input, outDir, args) {
  fs.rmSync(outDir, { recursive: true, force: true });
  execFileSync(irrmap, [input, ...args, '--out', outDir], { stdio: ['ignore', 'ignore', 'inherit'] });
  return outDir;
}

// three.js from the node_modules/three folder `threeDir`: `importThree(file)` imports a file of it, after
// printing its version; exits 77 (ctest's SKIP_RETURN_CODE) where it is not installed.
export async function threeModules(threeDir) {
  if (!fs.existsSync(path.join(threeDir, 'package.json'))) {
    console.log(`three.js is not installed at ${threeDir}: run .ci/setup (npm ci of tests/irradiance/three)`);
    process.exit(77);
  }
  const importThree = (file) => import(pathToFileURL(path.join(threeDir, file)).href);
  const THREE = await importThree('build/three.module.js');
  console.log(`three.js ${readJson(path.join(threeDir, 'package.json')).version} (REVISION ${THREE.REVISION})`);
  return { THREE, importThree };
}

// "--name value" pairs of process.argv.
export function parseArgs(names) {
  const args = {};
  for (let i = 2; i < process.argv.length; i += 2) {
    const name = process.argv[i].replace(/^--/, '');
    if (!names.includes(name)) throw new Error(`unknown argument ${process.argv[i]} (use ${names.map((n) => '--' + n).join(' ')})`);
    args[name] = process.argv[i + 1];
  }
  for (const name of names) if (args[name] === undefined) throw new Error(`missing --${name}`);
  fs.mkdirSync(args.work ?? '.', { recursive: true });
  return args;
}

let failures = 0;
export function check(ok, message) {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${message}`);
  if (!ok) failures++;
}
export function finish() {
  if (failures) {
    console.log(`${failures} check(s) failed`);
    process.exit(1);
  }
}

// Unit vectors spread evenly over the sphere (a Fibonacci lattice).
export function sphereDirections(count) {
  const out = [];
  const golden = Math.PI * (3 - Math.sqrt(5));
  for (let i = 0; i < count; i++) {
    const y = 1 - (2 * (i + 0.5)) / count;
    const r = Math.sqrt(1 - y * y);
    out.push([r * Math.cos(golden * i), y, r * Math.sin(golden * i)]);
  }
  return out;
}

// LightProbeGenerator.fromCubeTexture draws each face on a canvas and reads its pixels back as bytes;
// this stand-in canvas (node has none) hands it each face's { width, height, data } unchanged (callers
// pass values times 255, as it divides by 255).
export function installCanvasStandIn() {
  globalThis.document = {
    createElement: () => {
      let image = null;
      return {
        getContext: () => ({
          drawImage: (drawn) => { image = drawn; },
          getImageData: () => ({ data: image.data, width: image.width, height: image.height }),
        }),
      };
    },
  };
}

export const degrees = (radians) => (radians * 180) / Math.PI;
export const angleBetween = (a, b) =>
  Math.acos(Math.min(1, Math.max(-1, (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / Math.hypot(...a) / Math.hypot(...b))));
export const readJson = (file) => JSON.parse(fs.readFileSync(file, 'utf8'));
export { path, fs };
