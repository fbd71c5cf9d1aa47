// The irradiance maps irrmap writes, loaded by three.js's own loaders (the version package-lock.json
// pins), as the README says three.js loads them or refuses them:
//   --map-format hdr-faces: HDRCubeTextureLoader.load of the six irradiance_{px,nx,py,ny,pz,nz}.hdr
//       gives a CubeTexture of six faces, and every texel holds the irradiance sh_three.json gives
//       (SphericalHarmonics3.getIrradianceAt) at the direction where three.js shows that texel of a
//       CubeTexture: the direction LightProbeGenerator.fromCubeTexture, three's own code, assigns it;
//   --map-format dds: DDSLoader refuses DXGI format 10 (it takes only BC6H of the float formats);
//   --map-format ktx2: KTX2Loader loads the RGBA16F cube as a 2D DataTexture, not a cube (its path for
//       uncompressed formats ignores faceCount);
//   --map-format ktx (Filament's): KTXLoader warns that it takes compressed formats only.
//
// node three_loaders_test.mjs --irrmap BIN --three NODE_MODULES/three --work DIR
import {
  check, finish, fs, installCanvasStandIn, parseArgs, path, readJson, runIrrmap, threeModules,
} from './frame_test_support.mjs';

const args = parseArgs(['irrmap', 'three', 'work']);
const { THREE, importThree } = await threeModules(args.three);
const { HDRCubeTextureLoader } = await importThree('examples/jsm/loaders/HDRCubeTextureLoader.js');
const { DDSLoader } = await importThree('examples/jsm/loaders/DDSLoader.js');
const { KTX2Loader } = await importThree('examples/jsm/loaders/KTX2Loader.js');
const { KTXLoader } = await importThree('examples/jsm/loaders/KTXLoader.js');
const { LightProbeGenerator } = await importThree('examples/jsm/lights/LightProbeGenerator.js');

// What node lacks of a browser, for the loaders' own load(): FileLoader fetches each URL (node's fetch
// takes data: URLs, not files) and reports progress with a ProgressEvent.
globalThis.ProgressEvent ??= class extends Event {
  constructor(type, init = {}) { super(type); Object.assign(this, init); }
};
const manager = new THREE.LoadingManager();
manager.setURLModifier((file) => `data:application/octet-stream;base64,${fs.readFileSync(file).toString('base64')}`);
installCanvasStandIn();

const kMapSize = 8;
const common = ['sky', '--face-size', '16', '--order', 'order2', '--no-ground-truth', '--map-size', `${kMapSize}`];
const mapOf = (format) => runIrrmap(args.irrmap, common[0], path.join(args.work, format),
  [...common.slice(1), '--map-format', format, '--sh-export', 'three']);

// --- hdr-faces: a CubeTexture --------------------------------------------------------------------
const faceNames = ['px', 'nx', 'py', 'ny', 'pz', 'nz'];  // the order HDRCubeTextureLoader takes URLs in
const facesDir = mapOf('hdr-faces');
const urls = faceNames.map((face) => path.join(facesDir, `irradiance_${face}.hdr`));
const cube = await new Promise((resolve, reject) =>
  new HDRCubeTextureLoader(manager).setDataType(THREE.FloatType).load(urls, resolve, undefined, reject));
check(cube.isCubeTexture === true && cube.images.length === 6, `hdr-faces: HDRCubeTextureLoader gives a CubeTexture of ${cube.images.length} faces`);
check(cube.images.every((face) => face.image.width === kMapSize && face.image.height === kMapSize),
  `hdr-faces: every face is ${kMapSize} x ${kMapSize}`);

// Where three.js shows texel i of face f of a CubeTexture: the direction LightProbeGenerator gives it,
// read back from the probe of a cube with that one texel lit (its band-1 coefficients are 0.488603
// times y, z and x of the direction).
function shownDirection(f, i) {
  const images = Array.from({ length: 6 }, (_, face) => {
    const data = new Float32Array(kMapSize * kMapSize * 4);
    if (face === f) data[4 * i] = 255;
    return { width: kMapSize, height: kMapSize, data };
  });
  const texture = new THREE.CubeTexture(images);
  texture.colorSpace = THREE.LinearSRGBColorSpace;
  const c = LightProbeGenerator.fromCubeTexture(texture).sh.coefficients;
  return new THREE.Vector3(c[3].x, c[1].x, c[2].x).normalize();
}

const json = readJson(path.join(facesDir, 'sh_three.json'));
check(json.view === 'cube_texture', `hdr-faces: sh_three.json assumes a CubeTexture (view "${json.view}")`);
const probe = new THREE.LightProbe(new THREE.SphericalHarmonics3().fromArray(json.sh), json.intensity);
const expected = (d) => probe.sh.getIrradianceAt(d, new THREE.Vector3()).multiplyScalar(probe.intensity);

// The largest difference between each texel and the export at the direction `where` gives it, as a
// fraction of the export's peak over the texels.
function worstTexelDifference(where) {
  let worst = 0, peak = 0;
  cube.images.forEach((face, f) => {
    for (let i = 0; i < kMapSize * kMapSize; i++) {
      const e = expected(where(f, i));
      const texel = face.image.data.subarray(4 * i, 4 * i + 3);
      peak = Math.max(peak, e.x, e.y, e.z);
      worst = Math.max(worst, Math.abs(texel[0] - e.x), Math.abs(texel[1] - e.y), Math.abs(texel[2] - e.z));
    }
  });
  return worst / peak;
}
// RGBE keeps 8 bits of mantissa (irrmap's writer rounds to within 1/256 of the largest channel), and
// three.js decodes a mantissa m as m / 255 where Radiance and OpenImageIO take m / 256 (0.39 %):
// 1 % of the peak covers both. Faces in another order, or one mirrored, miss by tens of percent.
const kTolerance = 0.01;
const directions = Array.from({ length: 6 }, (_, f) => Array.from({ length: kMapSize * kMapSize }, (_, i) => shownDirection(f, i)));
const worst = worstTexelDifference((f, i) => directions[f][i]);
check(worst < kTolerance, `hdr-faces: every texel against sh_three.json where three.js shows it: worst ${(100 * worst).toFixed(3)} % of the peak`);
const mirrored = worstTexelDifference((f, i) => directions[f][i].clone().setX(-directions[f][i].x));
check(mirrored > 10 * kTolerance, `hdr-faces: the same faces shown mirrored in x would miss by ${(100 * mirrored).toFixed(1)} % (the check tells frames apart)`);
const swapped = worstTexelDifference((f, i) => directions[f ^ 1][i]);
check(swapped > 10 * kTolerance, `hdr-faces: each face swapped with its opposite would miss by ${(100 * swapped).toFixed(1)} %`);

// --- dds, ktx2 and ktx: what three.js makes of them ------------------------------------------------------
// A file's bytes as an ArrayBuffer of their own (a small file's Buffer shares node's pool from some offset).
const arrayBufferOf = (file) => {
  const bytes = fs.readFileSync(file);
  return bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);
};
// DDSLoader.parse reports an unsupported format on console.error and returns no levels.
const errors = [];
const consoleError = console.error;
console.error = (...parts) => errors.push(parts.join(' '));
const dds = new DDSLoader().parse(arrayBufferOf(path.join(mapOf('dds'), 'irradiance.dds')), true);
console.error = consoleError;
check(dds.mipmaps.length === 0 && errors.some((e) => /Unsupported DXGI_FORMAT code\s+10\b/.test(e)),
  `dds: DDSLoader refuses DXGI format 10 ("${errors.join('; ')}"), as the README says`);

// KTX2Loader wants a renderer's extensions first; none of them matters to an uncompressed format.
const ktx2Loader = new KTX2Loader(manager).detectSupport({ extensions: { has: () => false } });
const ktx2 = await new Promise((resolve, reject) =>
  ktx2Loader.load(path.join(mapOf('ktx2'), 'irradiance.ktx2'), resolve, undefined, reject));
check(ktx2.isDataTexture === true && !ktx2.isCubeTexture && !ktx2.isCompressedCubeTexture && ktx2.image.width === kMapSize,
  `ktx2: KTX2Loader loads the RGBA16F cube as a ${ktx2.image.width} x ${ktx2.image.height} DataTexture, not a cube, as the README says`);
// KTXLoader (KTX 1.1) warns that it takes compressed formats only (it then hands Filament's GL_RGBA16F on
// as if it were a compressed format's enumerant, which no renderer of three's uploads).
const warnings = [];
const consoleWarn = console.warn;
console.warn = (...parts) => warnings.push(parts.join(' '));
const ktx = new KTXLoader().parse(arrayBufferOf(path.join(mapOf('ktx'), 'irradiance.ktx')), true);
console.warn = consoleWarn;
check(warnings.some((w) => w.includes('only compressed formats currently supported')) && ktx.format === 0x881a,
  `ktx: KTXLoader warns "${warnings.join('; ')}" and passes on GL_RGBA16F (${ktx.format}) as a compressed format, as the README says`);
finish();
