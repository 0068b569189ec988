// btflut-three.js: a material exported by `btflut export M.btflut -o M/` (docs/engines.md) as a
// three.js material, drawn by the export's own GLSL ES include (btflut_es.glsl). Every kind:
// `luts` (one reference), `model`, `references` and `learned` (banks with a predictor). Needs
// src/web/btflut_material.js (the reader `export --web`'s page uses too) loaded first.
//
//   const relit = await btflutThree.load(THREE, 'M/');   // a THREE.RawShaderMaterial
//   mesh.material = relit.material;
//   relit.setLight(new THREE.Vector3(x, y, z));          // in the material's tangent frame
//   relit.setView(new THREE.Vector3(x, y, z));           // towards the camera, likewise (default: frontal)
//
// The view picks a bank of views' nearest view layer; a learned model of views also predicts
// at it. A learned material draws by its decoder specialised to it (btflut_network.glsl), its
// frame at the light computed in JavaScript when the light or view is set; with
// `{framePerFragment: true}` the shader computes it per fragment instead (a curved mesh whose
// light varies per fragment; the frame's multiply-adds, material.json's, each pixel).
// A classic script (no modules), so it runs from file://. `THREE` is whichever three.js the page
// loaded: Debian's (r111, a classic script) or current ones (0.187, an ES module: pass the
// module's namespace); tested with both (tests/browser_check.sh). WebGL2 only: the include needs
// 3D and array textures; the LUTs are half floats, which WebGL2 filters. Copyright the btflut
// authors; MIT licence.
(function (global) {
  'use strict';

  function readFile(url) {  // XMLHttpRequest: fetch() refuses file:// URLs
    return new Promise((resolve, reject) => {
      const request = new XMLHttpRequest();
      request.open('GET', url);
      request.responseType = 'arraybuffer';
      request.onload = () => (request.status === 0 || request.status === 200) && request.response
        ? resolve(new Uint8Array(request.response)) : reject(new Error(url + ': cannot read (status ' + request.status + ')'));
      request.onerror = () => reject(new Error(url + ': cannot read'));
      request.send();
    });
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

  // After btflut_es.glsl and btflutMaterial.fragmentHead (the uniforms, relight()).
  // `lightTangent`: the light in the tangent frame (for a curved mesh, transform it per fragment
  // by the TBN, as docs/engines.md says).
  const fragmentMain = btflutMaterial.fragmentHead + `
uniform vec3 lightTangent;
uniform vec3 viewTangent;  // the view (towards the camera) in the tangent frame: which view layer, and a learned model of views
uniform float exposure;
in vec2 textureUv;
out vec4 colour;
void main() {
    vec2 texel = floor(textureUv * size);
    uvec2 pixel = uvec2(mod(vec2(texel.x, size.y - 1.0 - texel.y), size));  // image rows, top first: btflut's dither
    colour = vec4(min(relight(textureUv, lightTangent, viewTangent, pixel) * exposure, 1.0), 1.0);  // sRGB-encoded, as the reference
}
`;

  function texture2D(THREE, image, filter) {
    const half = image.rgba instanceof Uint16Array;
    const t = new THREE.DataTexture(image.rgba, image.width, image.height, THREE.RGBAFormat,
                                    half ? THREE.HalfFloatType : THREE.UnsignedByteType);
    t.magFilter = t.minFilter = filter;
    t.wrapS = t.wrapT = THREE.RepeatWrapping;
    t.generateMipmaps = false;
    t.flipY = false;
    t.unpackAlignment = 1;
    t.needsUpdate = true;
    return t;
  }

  // three.js renamed its data textures (r137: DataTexture3D -> Data3DTexture, DataTexture2DArray
  // -> DataArrayTexture) and wants GLSL 3 shaders without their #version line (r118: glslVersion).
  const data3D = (THREE) => THREE.Data3DTexture || THREE.DataTexture3D;
  const dataArray = (THREE) => THREE.DataArrayTexture || THREE.DataTexture2DArray;
  function glsl3(THREE, vertex, fragment) {
    if (THREE.GLSL3 === undefined) return {vertexShader: vertex, fragmentShader: fragment};
    const bare = (source) => source.replace(/^#version 300 es\n/, '');
    return {vertexShader: bare(vertex), fragmentShader: bare(fragment), glslVersion: THREE.GLSL3};
  }

  function arrayTexture(THREE, data, width, height, depth, type, filter) {
    const t = new (dataArray(THREE))(data, width, height, depth);
    t.format = THREE.RGBAFormat;
    t.type = type;
    t.magFilter = t.minFilter = filter;
    t.wrapS = t.wrapT = THREE.RepeatWrapping;
    t.generateMipmaps = false;
    t.needsUpdate = true;
    return t;
  }

  // Loads the export in `folder` (a URL ending in '/'); `options.dither` (default true),
  // `options.framePerFragment` (default false).
  async function load(THREE, folder, options) {
    const text = new TextDecoder();
    const json = JSON.parse(text.decode(await readFile(folder + 'material.json')));
    const include = text.decode(await readFile(folder + 'btflut_es.glsl'));
    const m = await btflutMaterial.prepare(json, (file) => readFile(folder + file), include);
    const dither = !options || options.dither !== false;
    m.material.dither = m.predictor.dither = dither;

    const luts = new (data3D(THREE))(m.luts.halves, m.luts.width, m.luts.height, m.luts.depth);
    luts.format = m.luts.channels === 1 ? THREE.RedFormat : THREE.RGBAFormat;
    luts.type = THREE.HalfFloatType;
    luts.magFilter = luts.minFilter = THREE.LinearFilter;
    luts.wrapS = luts.wrapT = luts.wrapR = THREE.ClampToEdgeWrapping;
    luts.generateMipmaps = false;
    luts.unpackAlignment = 2;
    luts.needsUpdate = true;
    const unusedArray = arrayTexture(THREE, new Float32Array(4), 1, 1, 1, THREE.FloatType, THREE.NearestFilter);
    const unused2D = texture2D(THREE, {width: 1, height: 1, rgba: new Uint8Array(4)}, THREE.NearestFilter);
    const uniforms = {
      luts: {value: luts},
      reference: {value: m.reference ? texture2D(THREE, m.reference, THREE.LinearFilter) : unused2D},
      planes: {value: m.planes ? arrayTexture(THREE, m.planes.rgba, m.planes.width, m.planes.height, m.planes.layers,
                                              THREE.UnsignedByteType, THREE.LinearFilter) : unusedArray},
      weights: {value: m.weights ? arrayTexture(THREE, m.weights.data, m.weights.size, m.weights.size, m.weights.layers,
                                                THREE.FloatType, THREE.NearestFilter) : unusedArray},
      labels: {value: m.labels ? texture2D(THREE, m.labels, THREE.NearestFilter) : unused2D},
      hasPredictor: {value: m.kind !== 'luts'}, lightTangent: {value: new THREE.Vector3(0, 0, 1)}, exposure: {value: 1},
      viewTangent: {value: new THREE.Vector3(0, 0, 1)}, layers: {value: m.layerViews.length / 3},
      layerViews: {value: Array.from({length: 16}, (_, k) =>
        k < m.layerViews.length / 3 ? new THREE.Vector3(...m.layerViews.slice(3 * k, 3 * k + 3)) : new THREE.Vector3(0, 0, 1))},
      size: {value: new THREE.Vector2(m.size[0], m.size[1])}, material: {value: m.material}, predictor: {value: m.predictor},
      // What a kind's shader reads per light change (a learned decoder's frame), computed here
      // once per light change, or per fragment with options.framePerFragment (a curved mesh's
      // varying light).
      framePerFragment: {value: !!(options && options.framePerFragment)}};
    // btflutMaterial.frameUniforms gives them as [name, components, values]; 'frame.field[0]' is
    // the array `field` of the struct uniform `frame`, which three.js sets from an object.
    const vector = (values) => values.length === 4 ? new THREE.Vector4(...values) : new THREE.Vector3(...values);
    const updateFrame = () => {
      const l = uniforms.lightTangent.value, v = uniforms.viewTangent.value;
      for (const [name, n, values] of btflutMaterial.frameUniforms(m, [l.x, l.y, l.z], [v.x, v.y, v.z])) {
        const [, struct, field, array] = name.match(/^(\w+)\.(\w+)(\[0\])?$/);
        const vectors = Array.from({length: values.length / n}, (_, k) => vector(values.slice(n * k, n * k + n)));
        (uniforms[struct] = uniforms[struct] || {value: {}}).value[field] = array ? vectors : vectors[0];
      }
    };
    updateFrame();
    const material = new THREE.RawShaderMaterial(
      {uniforms, ...glsl3(THREE, vertexShader, '#version 300 es\n' + btflutMaterial.shaderStart(m, include) + fragmentMain)});
    return {
      material, json,
      setLight(direction) { uniforms.lightTangent.value.copy(direction).normalize(); updateFrame(); },
      setView(direction) { uniforms.viewTangent.value.copy(direction).normalize(); updateFrame(); },
      setExposure(value) { uniforms.exposure.value = value; }};
  }

  global.btflutThree = {load};
})(typeof window !== 'undefined' ? window : globalThis);
