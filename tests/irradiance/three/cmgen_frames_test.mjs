// irrmap --sh-export filament against Filament's own cmgen (Debian's libfilament-tools) on the same
// files: a small light at known places of a lat-long panorama and of a cube-map cross. cmgen runs
// with windowing off (--sh-window=no, as irrmap's default --window none) and its default mirror, the
// view sh_filament.txt assumes; with --no-mirror, the other view its convention text names (sh[3],
// sh[4] and sh[7] negated). Both sets of nine lines are evaluated with Filament's shader polynomial
// over the sphere.
//
// node cmgen_frames_test.mjs --irrmap BIN --cmgen BIN --work DIR
import { execFileSync } from 'node:child_process';
import {
  FloatImage, check, finish, fs, horizontalCross, parseArgs, path, runIrrmap, sphereDirections, writeHdr,
} from './frame_test_support.mjs';

const args = parseArgs(['irrmap', 'cmgen', 'work']);

// The nine "(r, g, b); // L00, ..." lines both cmgen --sh-shader and sh_filament.txt hold.
function readNineLines(file) {
  const rows = [];
  for (const line of fs.readFileSync(file, 'utf8').split('\n')) {
    const match = /^\(\s*([-0-9.e+]+),\s*([-0-9.e+]+),\s*([-0-9.e+]+)\);/.exec(line);
    if (match) rows.push(match.slice(1, 4).map(Number));
  }
  if (rows.length !== 9) throw new Error(`${file}: ${rows.length} coefficient lines, not 9`);
  return rows;
}

// Filament's Irradiance_SphericalHarmonics before its max(0, ...): sum sh[i] p_i(n).
function filamentIrradiance(sh, [x, y, z]) {
  const p = [1, y, z, x, y * x, y * z, 3 * z * z - 1, z * x, x * x - y * y];
  return [0, 1, 2].map((c) => p.reduce((sum, pi, i) => sum + sh[i][c] * pi, 0));
}

function worstDifference(sh, reference, directions) {
  let worst = 0, peak = 0;
  for (const d of directions) {
    const e = filamentIrradiance(sh, d), r = filamentIrradiance(reference, d);
    peak = Math.max(peak, ...r);
    worst = Math.max(worst, ...e.map((value, c) => Math.abs(value - r[c])));
  }
  return worst / peak;
}

function cmgen(file, name, mirror) {
  const out = path.join(args.work, `${name}_cmgen${mirror ? '' : '_no_mirror'}.txt`);
  execFileSync(args.cmgen, ['-q', '--sh=3', '--sh-shader', '--sh-window=no', ...(mirror ? [] : ['--no-mirror']),
    `--sh-output=${out}`, file], { stdio: ['ignore', 'ignore', 'inherit'] });
  return readNineLines(out);
}

const directions = sphereDirections(4000);
// cmgen resamples a panorama at nearest pixels, spreading u over W - 1 pixels (a shift of up to half a
// pixel), irrmap with a B-spline, and the two weight cube texels differently: measured 0.4-1.6 % of
// the peak on the panoramas below, 0.2 % on the crosses. 3 % covers that; the wrong mirror or a 90
// degree turn misses by 25 % and more.
const kTolerance = 0.03;
const negated = (sh) => sh.map((row, i) => ([3, 4, 7].includes(i) ? row.map((v) => -v) : row));

function compare(file, layout, name) {
  const out = runIrrmap(args.irrmap, file, path.join(args.work, name),
    ['--layout', layout, ...(layout === 'latlong' ? ['--face-size', '256'] : []), '--coefficients-only', '--sh-export', 'filament']);
  const exported = readNineLines(path.join(out, 'sh_filament.txt'));
  const mirrored = worstDifference(exported, cmgen(file, name, true), directions);
  check(mirrored < kTolerance, `${name}: sh_filament.txt against cmgen (mirror on, window off): worst ${(100 * mirrored).toFixed(3)} % of the peak`);
  const unmirrored = worstDifference(negated(exported), cmgen(file, name, false), directions);
  check(unmirrored < kTolerance, `${name}: sh[3], sh[4], sh[7] negated against cmgen --no-mirror: worst ${(100 * unmirrored).toFixed(3)} % of the peak`);
}

// Panoramas: a smooth light (a Gaussian of 5 degrees on the sphere) centred at image point (u, t),
// t from the top. cmgen samples a panorama at nearest pixels without weighting them by area, which
// loses or gains up to 9 % of a light a few pixels wide; a smooth one on a 1024 x 512 image it
// resamples to about 1 %.
const kWidth = 1024, kHeight = 512, kLightWidth = (5 * Math.PI) / 180;
for (const [u, t] of [[0.5, 0.5], [0.75, 0.5], [0.125, 0.25], [0.625, 0.8125]]) {
  const image = new FloatImage(kWidth, kHeight, [0.02, 0.02, 0.02]);
  const [longitude, latitude] = [2 * Math.PI * u, Math.PI * (0.5 - t)];
  for (let y = 0; y < kHeight; y++) {
    const pixelLatitude = Math.PI * (0.5 - (y + 0.5) / kHeight);
    for (let x = 0; x < kWidth; x++) {
      const cosAngle = Math.sin(latitude) * Math.sin(pixelLatitude) +
        Math.cos(latitude) * Math.cos(pixelLatitude) * Math.cos(2 * Math.PI * (x + 0.5) / kWidth - longitude);
      const light = 20 * Math.exp(-((Math.acos(Math.min(1, cosAngle)) / kLightWidth) ** 2));
      image.set(x, y, [0.02 + light, 0.02 + 0.8 * light, 0.02 + 0.6 * light]);
    }
  }
  const name = `panorama_u${u}_t${t}`;
  const file = path.join(args.work, `${name}.hdr`);
  writeHdr(file, image);
  compare(file, 'latlong', name);
}

const kFace = 32;
for (const [face, x, y] of [[0, 16, 16], [4, 6, 10], [2, 20, 8]]) {
  const faces = Array.from({ length: 6 }, () => new FloatImage(kFace, kFace, [0.02, 0.02, 0.02]));
  for (const [dx, dy] of [[-1, -1], [0, -1], [-1, 0], [0, 0]]) faces[face].set(x + dx, y + dy, [60, 50, 40]);
  const name = `cube_face${face}_x${x}_y${y}`;
  const file = path.join(args.work, `${name}.hdr`);
  writeHdr(file, horizontalCross(faces, kFace));
  compare(file, 'hcross', name);
}
finish();
