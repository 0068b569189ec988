// btflut_material.js: a material exported by `btflut export` (docs/engines.md) read into the
// arrays WebGL2 uploads, and the values of the include's structs. Shared by the page that
// `btflut export --web` writes and the three.js recipe (examples/three/btflut-three.js).
//
//   const m = await btflutMaterial.prepare(json, async (file) => bytesOf(file));
//   m.luts: {width, height, depth, channels, halves}   a 3D texture, half floats (R16F or RGBA16F)
//   m.reference: {width, height, rgba}                 kind luts: RGBA8 (or half floats from 16 bits)
//   m.planes: {width, height, layers, rgba}            model, references, learned: an RGBA8 array texture
//   m.weights: {size, layers, data} | null             RGBA32F layers, nearest (learned: the decoder)
//   m.labels: {width, height, rgba} | null             RGBA8, nearest
//   m.network: {source} | undefined                    learned: its decoder specialised to it (GLSL ES, after the include)
//   btflutMaterial.frameUniforms(m, light, view)       what its shader reads per light: [[name, 3 or 4, values]]
//   btflutMaterial.learnedFrame(m, light, view)        learned: the decoder's frame at a light, BtflutLearnedFrame's fields
//   btflutMaterial.shaderStart(m, include)             the include and a learned material's decoder: the shader's start
//   m.material, m.predictor                            the fields of BtflutMaterial, BtflutPredictor
//   m.layerViews                                       each view layer's direction, tangent frame (flat x, y, z)
//   btflutMaterial.fragmentHead                        GLSL: those as uniforms, and relight()
//
// Images are decoded here, not by the browser: luts.png is 16-bit, and a browser's decoder gives
// 8 bits. Rows are stored bottom first (texture v = 0 at the image's bottom, so +v is image up,
// the tangent frame's +y). Copyright the btflut authors; MIT licence.
(function (global) {
  'use strict';

  // A PNG (8 or 16 bits; grey, grey-alpha, RGB or RGBA; not interlaced): rows top first,
  // channels interleaved, in a Uint8Array or Uint16Array.
  async function decodePng(bytes, name) {
    const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
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
  function toHalf(value) {  // a float in [0, 1] as an IEEE half, rounded to nearest
    floatView[0] = value;
    const bits = bitsView[0], exponent = ((bits >>> 23) & 255) - 112, mantissa = bits & 0x7fffff;
    if (exponent <= 0) return 0;  // below 2^-14: nothing the LUTs need
    return Math.min(0x7bff, (exponent << 10) + ((mantissa + 0x1000) >> 13));
  }

  // An image as RGBA, rows bottom first: 8-bit stays bytes, 16-bit becomes half floats.
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

  // The constants btflut's C++ shares with its shaders (kind ids, the most planes), as the
  // include (`btflut_es.glsl`'s text) defines them: one source for C++, GLSL and this reader.
  function constants(include) {
    const out = {};
    for (const [, name, value] of include.matchAll(/^#define (BTFLUT_\w+) (-?\d+)\s*$/gm)) out[name] = Number(value);
    for (const name of ['BTFLUT_MAX_PLANES', 'BTFLUT_KIND_MODEL', 'BTFLUT_KIND_REFERENCES', 'BTFLUT_KIND_LEARNED'])
      if (!(name in out)) throw new Error('btflut_es.glsl: no ' + name + ' (an include older than this reader)');
    return out;
  }

  // `json`: material.json; `read(file)`: a promise of that file's bytes (a Uint8Array);
  // `include`: the text of the include the shader is built from (btflut_es.glsl).
  async function prepare(json, read, include) {
    const c = constants(include);
    if (json.format !== 'btflut-material') throw new Error('material.json: not a btflut material');
    if (json.version > 2) throw new Error('material.json: version ' + json.version + ' is newer than this page reads (2)');
    const png = async (file) => decodePng(await read(file), file);
    // The LUT grid: luts.png's rows are the 3D texture's rows, slice after slice; one channel,
    // or RGB as RGBA (no RGB half-float uploads).
    const lut = await png(json.luts.file);
    const g = json.luts.grid_size, entries = json.luts.entries;
    if (lut.width !== entries || lut.height % (g * g) !== 0 || lut.depth !== 16)
      throw new Error(json.luts.file + ': not the 16-bit ' + entries + ' x (' + g + ' x ' + g + ' x blocks) image material.json describes');
    const n = lut.channels === 1 ? 1 : 4, texels = entries * lut.height, halves = new Uint16Array(texels * n);
    for (let i = 0; i < texels; ++i)
      for (let c = 0; c < n; ++c) halves[i * n + c] = c < lut.channels ? toHalf(lut.samples[i * lut.channels + c] / 65535) : 0x3c00;
    const rgbLuts = json.colour === 'rgb';
    const out = {
      json, kind: json.kind, size: [json.reference.width, json.reference.height],
      luts: {width: entries, height: g, depth: lut.height / g, channels: n, halves},
      reference: null, planes: null, weights: null, labels: null,
      material: {layer: 0, rgbLuts, greyReference: json.reference.channels === 1, inputCode: json.lut_input_code,
                 outputCode: json.lut_output_code, dither: true},
      predictor: {kind: 0, basis: 0, order: 0, planes: 0, channels: 1, albedo: 0, scale: new Array(c.BTFLUT_MAX_PLANES).fill(0),
                  bias: new Array(c.BTFLUT_MAX_PLANES).fill(0), regions: 1, codes: 255, rgbLuts, greyOutput: false,
                  outputCode: json.lut_output_code, dither: true}};
    // The view layers' directions (at most 16, as the shader's array), unit vectors of the tangent frame.
    const views = (json.views || []).slice(0, 16);
    out.layerViews = views.flatMap((v) => {
      const t = v.view.theta * Math.PI / 180, p = v.view.phi * Math.PI / 180;
      return [Math.sin(t) * Math.cos(p), Math.sin(t) * Math.sin(p), Math.cos(t)];
    });
    if (json.kind === 'luts') {
      const reference = await png(json.reference.file);
      out.reference = {width: reference.width, height: reference.height, rgba: rgbaRows(reference)};
      return out;
    }
    const p = json.predictor;
    if (![c.BTFLUT_KIND_MODEL, c.BTFLUT_KIND_REFERENCES, c.BTFLUT_KIND_LEARNED].includes(p.kind_index))
      throw new Error('material.json: predictor kind ' + p.kind + ' is not one this page draws');
    const files = p.images.slice();  // the planes (or references), then the albedo: one array
    if (p.albedo) files.push(p.albedo.file);
    const images = [];
    for (const file of files) images.push(await png(file));
    const {width, height} = images[0];
    const layers = new Uint8Array(width * height * 4 * images.length);
    images.forEach((image, k) => {
      if (image.width !== width || image.height !== height || image.depth !== 8) throw new Error(files[k] + ': not 8-bit, or not the size of the other planes');
      layers.set(rgbaRows(image), k * width * height * 4);
    });
    out.planes = {width, height, layers: images.length, rgba: layers};
    out.size = [width, height];
    if (p.weights) {
      const bytes = await read(p.weights.file), s = p.weights.grid_size, count = p.weights.layers;
      if (bytes.byteLength !== s * s * count * 16) throw new Error(p.weights.file + ': not the ' + s + 'x' + s + 'x' + count + ' RGBA float32 layers material.json describes');
      out.weights = {size: s, layers: count, data: new Float32Array(bytes.slice().buffer)};
    }
    if (p.labels) {
      const labels = await png(p.labels.file);
      out.labels = {width: labels.width, height: labels.height, rgba: rgbaRows(labels)};
    }
    Object.assign(out.predictor, {
      kind: p.kind_index, basis: p.kind === 'model' ? p.basis_index : 0, order: p.order || 0, planes: p.planes,
      channels: p.channels, albedo: !p.albedo ? 0 : p.albedo.use === 'multiplies' ? 1 : 2, regions: p.regions, codes: p.codes,
      greyOutput: p.output_channels === 1});
    (p.scale || []).forEach((v, k) => { out.predictor.scale[k] = v; out.predictor.bias[k] = p.bias[k]; });
    // A learned material's decoder specialised to it (GLSL ES after the include; it defines
    // BTFLUT_NETWORK, which fragmentHead's relight() then draws by).
    if (p.network) out.network = {source: new TextDecoder().decode(await read(p.network.glsl))};
    return out;
  }

  // The light's (or view's) hemispherical harmonics of order 3: btflut.glsl's btflutBasisTerms.
  function hshTerms([x, y, z]) {
    let n = Math.hypot(x, y, z);
    if (z < 0) { z = 0; n = Math.hypot(x, y); }  // below the horizon: the horizon's
    const c = z / n, s = Math.sqrt(Math.max(0, c - c * c)), r = Math.hypot(x, y) / n;
    const ax = r > 0 ? x / n / r : 1, ay = r > 0 ? y / n / r : 0, pi = Math.PI;
    return [1 / Math.sqrt(2 * pi), Math.sqrt(6 / pi) * ax * s, Math.sqrt(3 / (2 * pi)) * (2 * c - 1),
            Math.sqrt(6 / pi) * ay * s, Math.sqrt(30 / pi) * (ax * ax - ay * ay) * (c * c - c),
            Math.sqrt(30 / pi) * ax * (2 * c - 1) * s, Math.sqrt(5 / (2 * pi)) * (1 - 6 * c + 6 * c * c),
            Math.sqrt(30 / pi) * ay * (2 * c - 1) * s, Math.sqrt(30 / pi) * 2 * ax * ay * (c * c - c)];
  }

  // What a material's shader reads per light change beside the light, [name, components (3 or
  // 4), values] for uniform3fv / uniform4fv: a learned decoder's frame (BtflutLearnedFrame, below),
  // none for the kinds whose weights the include computes (or a decoder drawn from its texture).
  function frameUniforms(m, light, view) {
    if (!m.network) return [];
    const f = learnedFrame(m, light, view);
    return [['learnedFrame.basis[0]', 4, f.basis], ['learnedFrame.offset', 3, f.offset],
            ['learnedFrame.hidden[0]', 4, f.hidden]];
  }

  // A learned material's frame at a light and view (unit vectors of the tangent frame): the
  // fields of btflut.glsl's BtflutLearnedFrame, what btflutNetworkFrame computes per fragment,
  // here once per light change (LearnedModel::lightFrame). From the decoder's texels
  // (weights.bin; btflut.glsl, "A learned model": a head, the codes' scale and bias, the
  // residual network's layers, the light network's).
  function learnedFrame(m, light, view) {
    const t = m.weights.data, texel = (k) => t.subarray(4 * k, 4 * k + 4);
    const [N, C, hidden, lightHidden] = texel(0), widths = texel(1), lightWidths = texel(2), F = texel(3)[0];
    const h = hshTerms(light);
    if (F > 9) h.push(...hshTerms(view).slice(1, 1 + F - 9));
    // The layer at texel `at`: its outputs' rows of ceil(inputs / 4) texels, then its biases.
    const layer = (at, inputs, outputs, x, first, elu) => {
      const n = Math.ceil(inputs / 4), y = [];
      for (let o = 0; o < outputs; ++o) {
        let sum = t[4 * (at + outputs * n) + o];
        for (let i = 0; i < x.length; ++i) sum += t[4 * (at + o * n) + first + i] * x[i];
        y.push(elu ? (sum > 0 ? sum : Math.exp(sum) - 1) : sum);
      }
      return y;
    };
    const residual = 4 + 2 * Math.ceil(N / 4);
    let at = residual, inputs = N + F;
    for (let k = 0; k <= hidden; ++k) {  // past the residual network: the light network
      const outputs = k < hidden ? widths[k] : C;
      at += outputs * Math.ceil(inputs / 4) + Math.ceil(outputs / 4);
      inputs = outputs;
    }
    let x = h;
    inputs = F;
    for (let k = 0; k <= lightHidden; ++k) {
      const outputs = k < lightHidden ? lightWidths[k] : C * (N + 1);
      x = layer(at, inputs, outputs, x, 0, k < lightHidden);
      at += outputs * Math.ceil(inputs / 4) + Math.ceil(outputs / 4);
      inputs = outputs;
    }
    const frame = {basis: new Float32Array(4 * 3 * 8), offset: new Float32Array(3), hidden: new Float32Array(4 * 16)};
    for (let c = 0; c < C; ++c)
      for (let k = 0; k <= N; ++k) {
        const value = x[c * (N + 1) + k];
        if (k === N) frame.offset[c] = value;
        else frame.basis[4 * (Math.floor(k / 4) * 3 + c) + k % 4] = value;
      }
    frame.hidden.set(layer(residual, N + F, widths[0], h, N, false));  // the first layer at codes 0
    return frame;
  }

  // GLSL ES to put after the include: the material's textures and structs as uniforms, and
  // relight(uv, lightTangent, viewTangent, pixel) for every kind: the view layer nearest the
  // view (a learned model of views also predicts at the view); relight(uv, lightTangent, pixel)
  // for a frontal view.
  const fragmentHead = `
uniform sampler3D luts;
uniform highp sampler2D reference;
uniform sampler2DArray planes, weights;
uniform highp sampler2D labels;
uniform BtflutMaterial material;
uniform BtflutPredictor predictor;
uniform bool hasPredictor;
uniform vec2 size;  // the material's texels
uniform int layers;
uniform vec3 layerViews[16];  // each view layer's direction in the tangent frame

#ifdef BTFLUT_NETWORK
// A learned material's decoder specialised to it: its frame at the light from the CPU
// (btflutMaterial.learnedFrame, once per light change), or per fragment where the light varies
// over the surface (a sphere).
uniform BtflutLearnedFrame learnedFrame;
uniform bool framePerFragment;
#endif

vec3 relight(vec2 uv, vec3 lightTangent, vec3 viewTangent, uvec2 pixel) {
    int layer = 0;
    float best = -2.0;
    for (int k = 0; k < 16; ++k) {
        if (k >= layers) break;
        float c = dot(normalize(viewTangent), layerViews[k]);
        if (c > best) {
            best = c;
            layer = k;
        }
    }
    BtflutMaterial m = material;
    m.layer = layer;
#ifdef BTFLUT_NETWORK
    BtflutLearnedFrame frame = learnedFrame;
    if (framePerFragment) frame = btflutNetworkFrame(lightTangent, viewTangent);
    return btflutRelightPrediction(luts, planes, labels, predictor, uv, lightTangent, layer, pixel,
                                   btflutNetworkPrediction(planes, uv, frame));
#endif
    return hasPredictor ? btflutRelight(luts, planes, weights, labels, predictor, uv, lightTangent, viewTangent, layer, pixel)
                        : btflutRelight(luts, m, texture(reference, uv).rgb, lightTangent, pixel);
}
vec3 relight(vec2 uv, vec3 lightTangent, uvec2 pixel) { return relight(uv, lightTangent, vec3(0.0, 0.0, 1.0), pixel); }
`;

  // The source the fragment shader starts with: the include, then a learned material's decoder.
  const shaderStart = (m, include) => include + (m.network ? m.network.source : '');

  global.btflutMaterial = {decodePng, constants, prepare, toHalf, fragmentHead, frameUniforms, learnedFrame,
                           shaderStart};
})(typeof window !== 'undefined' ? window : globalThis);
