// btflut-three.js: a material exported by `btflut export M.btflut -o M/` (docs/engines.md) as a
// three.js material, drawn by the export's own GLSL ES include (btflut_es.glsl). Every kind:
// `luts` (one reference), `model` and `references` (banks with a predictor).
//
//   const relit = await btflutThree.load(THREE, 'M/');   // a THREE.RawShaderMaterial
//   mesh.material = relit.material;
//   relit.setLight(new THREE.Vector3(x, y, z));          // in the material's tangent frame
//
// A classic script (no modules), so it runs from file://. WebGL2 only: the include needs 3D and
// array textures. PNGs are decoded here, not by the browser, because luts.png is 16-bit and a
// browser's decoder gives 8 bits; the LUTs are uploaded as half floats (filterable in WebGL2).
// Copyright the btflut authors; MIT licence.
(function (global) {
  'use strict';

  function readFile(url) {  // XMLHttpRequest: fetch() refuses file:// URLs
    return new Promise((resolve, reject) => {
      const request = new XMLHttpRequest();
      request.open('GET', url);
      request.responseType = 'arraybuffer';
      request.onload = () => (request.status === 0 || request.status === 200) && request.response
        ? resolve(request.response) : reject(new Error(url + ': cannot read (status ' + request.status + ')'));
      request.onerror = () => reject(new Error(url + ': cannot read'));
      request.send();
    });
  }

  // A PNG (8 or 16 bits, grey, grey-alpha, RGB or RGBA, not interlaced): rows top first,
  // channels interleaved, in a Uint8Array or Uint16Array.
  async function decodePng(buffer, name) {
    const bytes = new Uint8Array(buffer), view = new DataView(buffer);
    const signature = [137, 80, 78, 71, 13, 10, 26, 10];
    if (bytes.length < 8 || signature.some((b, i) => bytes[i] !== b)) throw new Error(name + ': not a PNG file');
    let width = 0, height = 0, depth = 0, type = -1;
    const data = [];
    for (let at = 8; at + 8 <= bytes.length;) {
      const length = view.getUint32(at), kind = String.fromCharCode(...bytes.subarray(at + 4, at + 8));
      if (at + 12 + length > bytes.length) throw new Error(name + ': truncated ' + kind + ' chunk');
      const body = bytes.subarray(at + 8, at + 8 + length);
      if (kind === 'IHDR') {
        width = view.getUint32(at + 8); height = view.getUint32(at + 12); depth = body[8]; type = body[9];
        if (body[12] !== 0) throw new Error(name + ': interlaced PNGs are not read');
      } else if (kind === 'IDAT') {
        data.push(body);
      } else if (kind === 'IEND') {
        break;
      }
      at += 12 + length;
    }
    const channels = {0: 1, 2: 3, 4: 2, 6: 4}[type];
    if (!channels || (depth !== 8 && depth !== 16)) throw new Error(name + ': PNG colour type ' + type + ', depth ' + depth + ' not read');
    const stream = new Blob(data).stream().pipeThrough(new DecompressionStream('deflate'));
    const raw = new Uint8Array(await new Response(stream).arrayBuffer());
    const step = channels * depth / 8, stride = width * step;
    if (raw.length < height * (stride + 1)) throw new Error(name + ': truncated image data');
    const out = new Uint8Array(height * stride);
    for (let y = 0; y < height; ++y) {
      const filter = raw[y * (stride + 1)], line = raw.subarray(y * (stride + 1) + 1, (y + 1) * (stride + 1));
      const row = out.subarray(y * stride, (y + 1) * stride), up = y > 0 ? out.subarray((y - 1) * stride, y * stride) : null;
      for (let i = 0; i < stride; ++i) {
        const a = i >= step ? row[i - step] : 0, b = up ? up[i] : 0, c = up && i >= step ? up[i - step] : 0;
        let predictor = 0;
        if (filter === 1) predictor = a;
        else if (filter === 2) predictor = b;
        else if (filter === 3) predictor = (a + b) >> 1;
        else if (filter === 4) {
          const p = a + b - c, pa = Math.abs(p - a), pb = Math.abs(p - b), pc = Math.abs(p - c);
          predictor = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
        } else if (filter !== 0) throw new Error(name + ': bad PNG filter ' + filter);
        row[i] = (line[i] + predictor) & 255;
      }
    }
    let samples = out;
    if (depth === 16) {
      samples = new Uint16Array(width * height * channels);
      for (let i = 0; i < samples.length; ++i) samples[i] = (out[2 * i] << 8) | out[2 * i + 1];
    }
    return {width, height, channels, depth, samples};
  }

  const floatView = new Float32Array(1), bitsView = new Uint32Array(floatView.buffer);
  function toHalf(value) {  // a float in [0, 1] as IEEE half, rounded to nearest
    floatView[0] = value;
    const bits = bitsView[0], exponent = ((bits >>> 23) & 255) - 112, mantissa = bits & 0x7fffff;
    if (exponent <= 0) return 0;  // below 2^-14: nothing the LUTs need
    return Math.min(0x7bff, (exponent << 10) + ((mantissa + 0x1000) >> 13));
  }

  // An image as RGBA, rows bottom first (texture coordinate v = 0 at the image's bottom, so +v is
  // image up, the tangent frame's +y): 8-bit stays bytes, 16-bit becomes half floats.
  function rgbaRows(image) {
    const {width, height, channels, depth, samples} = image;
    const out = depth === 16 ? new Uint16Array(width * height * 4) : new Uint8Array(width * height * 4);
    const top = depth === 16 ? 65535 : 255;
    for (let y = 0; y < height; ++y)
      for (let x = 0; x < width; ++x) {
        const from = ((height - 1 - y) * width + x) * channels, to = (y * width + x) * 4;
        for (let c = 0; c < 4; ++c) {
          const v = c < 3 ? samples[from + (channels < 3 ? 0 : c)] : channels === 2 || channels === 4 ? samples[from + channels - 1] : top;
          out[to + c] = depth === 16 ? toHalf(v / top) : v;
        }
      }
    return out;
  }

  const vertexShader = `#version 300 es
uniform mat4 modelViewMatrix, projectionMatrix;
in vec3 position;
in vec2 uv;
out vec2 textureUv;
void main() {
    textureUv = uv;
    gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0);
}
`;

  // After btflut_es.glsl. `lightTangent`: the light in the tangent frame (for a curved mesh,
  // transform it per fragment by the TBN, as docs/engines.md says).
  const fragmentMain = `
uniform sampler3D luts;
uniform highp sampler2D reference;
uniform sampler2DArray planes, weights;
uniform highp sampler2D labels;
uniform BtflutMaterial material;
uniform BtflutPredictor predictor;
uniform bool hasPredictor;
uniform vec2 size;             // the material's texels
uniform vec3 lightTangent;
uniform float exposure;
in vec2 textureUv;
out vec4 colour;
void main() {
    vec2 texel = floor(textureUv * size);
    uvec2 pixel = uvec2(mod(vec2(texel.x, size.y - 1.0 - texel.y), size));  // image rows, top first: btflut's dither
    vec3 relit = hasPredictor
        ? btflutRelight(luts, planes, weights, labels, predictor, textureUv, lightTangent, pixel)
        : btflutRelight(luts, material, texture(reference, textureUv).rgb, lightTangent, pixel);
    colour = vec4(min(relit * exposure, 1.0), 1.0);  // sRGB-encoded, as the reference
}
`;

  function texture2D(THREE, rows, image, filter, format) {
    const t = new THREE.DataTexture(rows, image.width, image.height, format || THREE.RGBAFormat,
                                    rows instanceof Uint16Array ? THREE.HalfFloatType : THREE.UnsignedByteType);
    t.magFilter = t.minFilter = filter;
    t.wrapS = t.wrapT = THREE.RepeatWrapping;
    t.generateMipmaps = false;
    t.flipY = false;
    t.unpackAlignment = 1;
    t.needsUpdate = true;
    return t;
  }

  function arrayTexture(THREE, data, width, height, depth, type, filter) {
    const t = new THREE.DataTexture2DArray(data, width, height, depth);
    t.format = THREE.RGBAFormat;
    t.type = type;
    t.magFilter = t.minFilter = filter;
    t.wrapS = t.wrapT = THREE.RepeatWrapping;
    t.generateMipmaps = false;
    t.needsUpdate = true;
    return t;
  }

  // Loads the export in `folder` (a URL ending in '/'); `options.dither` (default true).
  async function load(THREE, folder, options) {
    const dither = !options || options.dither !== false;
    const text = new TextDecoder();
    const json = JSON.parse(text.decode(await readFile(folder + 'material.json')));
    if (json.format !== 'btflut-material') throw new Error(folder + 'material.json: not a btflut material');
    if (json.version > 2) throw new Error(folder + 'material.json: version ' + json.version + ' is newer than this loader reads (2)');
    const include = text.decode(await readFile(folder + 'btflut_es.glsl'));
    const png = async (file) => decodePng(await readFile(folder + file), folder + file);

    // The LUT grid: luts.png's rows are the 3D texture's rows, slice after slice.
    const lutImage = await png(json.luts.file);
    const g = json.luts.grid_size, entries = json.luts.entries;
    if (lutImage.width !== entries || lutImage.height % (g * g) !== 0 || lutImage.depth !== 16)
      throw new Error(folder + json.luts.file + ': not the 16-bit ' + entries + ' x (' + g + ' x ' + g + ' x blocks) image material.json describes');
    // One channel, or RGB as RGBA (three.js uploads no RGB half floats).
    const n = lutImage.channels === 1 ? 1 : 4, texels = entries * lutImage.height;
    const lutHalves = new Uint16Array(texels * n);
    for (let i = 0; i < texels; ++i)
      for (let c = 0; c < n; ++c) lutHalves[i * n + c] = c < lutImage.channels ? toHalf(lutImage.samples[i * lutImage.channels + c] / 65535) : 0x3c00;
    const luts = new THREE.DataTexture3D(lutHalves, entries, g, lutImage.height / g);
    luts.format = n === 1 ? THREE.RedFormat : THREE.RGBAFormat;
    luts.type = THREE.HalfFloatType;
    luts.magFilter = luts.minFilter = THREE.LinearFilter;
    luts.wrapS = luts.wrapT = luts.wrapR = THREE.ClampToEdgeWrapping;
    luts.generateMipmaps = false;
    luts.unpackAlignment = 2;
    luts.needsUpdate = true;

    const unusedArray = arrayTexture(THREE, new Float32Array(4), 1, 1, 1, THREE.FloatType, THREE.NearestFilter);
    const unused2D = texture2D(THREE, new Uint8Array(4), {width: 1, height: 1}, THREE.NearestFilter);
    const uniforms = {
      luts: {value: luts}, reference: {value: unused2D}, planes: {value: unusedArray}, weights: {value: unusedArray},
      labels: {value: unused2D}, hasPredictor: {value: json.kind !== 'luts'}, lightTangent: {value: new THREE.Vector3(0, 0, 1)},
      exposure: {value: 1}, size: {value: new THREE.Vector2(json.reference.width, json.reference.height)},
      material: {value: {layer: 0, rgbLuts: json.colour === 'rgb', greyReference: json.reference.channels === 1,
                         inputCode: json.lut_input_code, outputCode: json.lut_output_code, dither}},
      predictor: {value: {kind: 0, basis: 0, order: 0, planes: 0, channels: 1, albedo: 0, scale: new Array(32).fill(0),
                          bias: new Array(32).fill(0), regions: 1, codes: 255, rgbLuts: json.colour === 'rgb',
                          greyOutput: false, outputCode: json.lut_output_code, dither}}};

    if (json.kind === 'luts') {
      const reference = await png(json.reference.file);
      uniforms.reference.value = texture2D(THREE, rgbaRows(reference), reference, THREE.LinearFilter);
    } else {
      const p = json.predictor;
      // The planes (or references), then the albedo: one RGBA8 array.
      const files = p.images.slice();
      if (p.albedo) files.push(p.albedo.file);
      const images = [];
      for (const file of files) images.push(await png(file));
      const {width, height} = images[0];
      const layers = new Uint8Array(width * height * 4 * images.length);
      images.forEach((image, k) => {
        if (image.width !== width || image.height !== height || image.depth !== 8) throw new Error(folder + files[k] + ': not 8-bit, or not the size of the other planes');
        layers.set(rgbaRows(image), k * width * height * 4);
      });
      uniforms.planes.value = arrayTexture(THREE, layers, width, height, images.length, THREE.UnsignedByteType, THREE.LinearFilter);
      uniforms.size.value.set(width, height);
      if (p.weights) {
        const bytes = await readFile(folder + p.weights.file), s = p.weights.grid_size, count = p.weights.layers;
        if (bytes.byteLength !== s * s * count * 16) throw new Error(folder + p.weights.file + ': not the ' + s + 'x' + s + 'x' + count + ' RGBA float32 layers material.json describes');
        uniforms.weights.value = arrayTexture(THREE, new Float32Array(bytes), s, s, count, THREE.FloatType, THREE.NearestFilter);
      }
      if (p.labels) {
        const labels = await png(p.labels.file);
        uniforms.labels.value = texture2D(THREE, rgbaRows(labels), labels, THREE.NearestFilter);
      }
      Object.assign(uniforms.predictor.value, {
        kind: p.kind === 'model' ? 1 : 2, basis: p.kind === 'model' ? p.basis_index : 0, order: p.order || 0, planes: p.planes,
        channels: p.channels, albedo: !p.albedo ? 0 : p.albedo.use === 'multiplies' ? 1 : 2, regions: p.regions, codes: p.codes,
        greyOutput: p.output_channels === 1});
      (p.scale || []).forEach((v, k) => { uniforms.predictor.value.scale[k] = v; uniforms.predictor.value.bias[k] = p.bias[k]; });
    }

    const material = new THREE.RawShaderMaterial({
      uniforms, vertexShader, fragmentShader: '#version 300 es\n' + include + fragmentMain});
    return {
      material, json,
      setLight(direction) { uniforms.lightTangent.value.copy(direction).normalize(); },
      setExposure(value) { uniforms.exposure.value = value; }};
  }

  global.btflutThree = {load, decodePng};
})(typeof window !== 'undefined' ? window : globalThis);
