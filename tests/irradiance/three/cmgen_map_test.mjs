// irrmap --map-format ktx against Filament's own cmgen (Debian's libfilament-tools): cmgen turns
// irrmap's irradiance.exr (a cross) into the KTX 1.1 cube Filament loads (-x DIR: DIR_skybox.ktx, at
// --size the cross's face size, so no resampling), and irrmap's irradiance.ktx of the same map must be
// that cube: the same KTX 1.1 cube fields, and every texel the same to the precision of cmgen's
// R11F_G11F_B10F (6 and 5 bits of mantissa, no sign), which also shows both mirror the cube in x the
// same way.
//
// node cmgen_map_test.mjs --irrmap BIN --cmgen BIN --work DIR
import { execFileSync } from 'node:child_process';
import { check, finish, fs, parseArgs, path, runIrrmap } from './frame_test_support.mjs';

const args = parseArgs(['irrmap', 'cmgen', 'work']);

// A KTX 1.1 file as the specification lays it out: the header words after the identifier, then the
// first level's imageSize and its faces.
function readKtx1(file) {
  const bytes = fs.readFileSync(file);
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const names = ['endianness', 'glType', 'glTypeSize', 'glFormat', 'glInternalFormat', 'glBaseInternalFormat',
    'pixelWidth', 'pixelHeight', 'pixelDepth', 'numberOfArrayElements', 'numberOfFaces', 'numberOfMipmapLevels',
    'bytesOfKeyValueData'];
  const header = Object.fromEntries(names.map((name, i) => [name, view.getUint32(12 + 4 * i, true)]));
  const level = 64 + header.bytesOfKeyValueData;
  return { header, view, faceBytes: view.getUint32(level, true), data: level + 4 };
}

// Texel (x, y) of face f as RGB floats, for the two formats in play.
// cmgen writes glType GL_R11F_G11F_B10F (0x8C3A, the internal format's enumerant), which Filament's
// Ktx1Reader reads as UINT_10F_11F_11F_REV as it would the proper type 0x8C3B.
const kHalfFloat = 0x140b, kPackedFloatTypes = [0x8c3a, 0x8c3b];
function smallFloat(bits, mantissaBits) {  // unsigned, 5-bit exponent (bias 15), as GL's packed floats
  const exponent = bits >> mantissaBits, mantissa = bits & ((1 << mantissaBits) - 1);
  if (exponent === 0) return (mantissa / (1 << mantissaBits)) * 2 ** -14;
  return (1 + mantissa / (1 << mantissaBits)) * 2 ** (exponent - 15);
}
function halfFloat(bits) {
  const sign = bits & 0x8000 ? -1 : 1;
  return sign * smallFloat(bits & 0x7fff, 10);
}
function texel({ header, view, faceBytes, data }, f, x, y) {
  const at = data + f * faceBytes + (y * header.pixelWidth + x) * faceBytes / (header.pixelWidth * header.pixelHeight);
  if (header.glType === kHalfFloat) return [0, 1, 2].map((c) => halfFloat(view.getUint16(at + 2 * c, true)));
  if (kPackedFloatTypes.includes(header.glType)) {
    const word = view.getUint32(at, true);
    return [smallFloat(word & 0x7ff, 6), smallFloat((word >> 11) & 0x7ff, 6), smallFloat(word >>> 22, 5)];
  }
  throw new Error(`glType 0x${header.glType.toString(16)} is not one this test reads`);
}

const kSize = 16;
const common = ['--face-size', '32', '--no-ground-truth', '--map-size', `${kSize}`];
for (const environment of ['sky', 'studio']) {
  const exrDir = runIrrmap(args.irrmap, environment, path.join(args.work, `${environment}_exr`), [...common, '--map-format', 'exr']);
  const ktxDir = runIrrmap(args.irrmap, environment, path.join(args.work, `${environment}_ktx`), [...common, '--map-format', 'ktx']);
  const cmgenDir = path.join(args.work, `${environment}_cmgen`);
  fs.rmSync(cmgenDir, { recursive: true, force: true });
  execFileSync(args.cmgen, ['--quiet', '--format=ktx', `--size=${kSize}`, '-x', cmgenDir, path.join(exrDir, 'irradiance.exr')]);
  const cmgen = readKtx1(path.join(cmgenDir, `${path.basename(cmgenDir)}_skybox.ktx`));
  const ours = readKtx1(path.join(ktxDir, 'irradiance.ktx'));
  for (const field of ['endianness', 'pixelWidth', 'pixelHeight', 'pixelDepth', 'numberOfArrayElements', 'numberOfFaces', 'numberOfMipmapLevels']) {
    check(ours.header[field] === cmgen.header[field], `${environment}: ${field} ${ours.header[field]}, cmgen's ${cmgen.header[field]}`);
  }
  // R11F/G11F keep 6 bits of mantissa, B10F 5: within 2^-6 and 2^-5 of the value (rounded or cut);
  // a face in the wrong place or a missing mirror is off by far more on these maps.
  let worst = 0;
  for (let f = 0; f < 6; f++) {
    for (let y = 0; y < kSize; y++) {
      for (let x = 0; x < kSize; x++) {
        // cmgen's unsigned floats hold no negative value (a nine-term map rings below 0): 0 there.
        const a = texel(ours, f, x, y).map((v) => Math.max(v, 0)), b = texel(cmgen, f, x, y);
        for (let c = 0; c < 3; c++) worst = Math.max(worst, Math.abs(a[c] - b[c]) / (Math.abs(b[c]) * 2 ** (c === 2 ? -5 : -6) + 1e-6));
      }
    }
  }
  check(worst <= 1, `${environment}: every texel of irradiance.ktx is cmgen's skybox of irradiance.exr to R11F_G11F_B10F's precision ` +
    `(worst ${worst.toFixed(2)} of it)`);
}
finish();
