// The page rad-bake --html writes: shows the baked glb (embedded in the page) from rad-shade's
// camera with rad-shade's exposure, orbit controls, and one slider per light group that mixes the
// group lightmaps in the shader. Bundled with three.js into one script (web/build-viewer).
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const config = JSON.parse(document.getElementById('radiosity-config').textContent);

function decodeBase64(text) {
  const binary = atob(text.trim());
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; ++i) bytes[i] = binary.charCodeAt(i);
  return bytes.buffer;
}

// Mixes the group lightmaps: sum of weight x (linear) texel, times the exposure ratio. sRGB
// textures are decoded by the GPU; the output is encoded to sRGB like rad-shade's PNG.
function mixingMaterial(textures, doubleSided) {
  const count = textures.length;
  return new THREE.ShaderMaterial({
    defines: { GROUPS: count },
    uniforms: {
      lightmaps: { value: textures },
      weights: { value: new Array(count).fill(1) },
      scale: { value: 1 },
    },
    side: doubleSided ? THREE.DoubleSide : THREE.FrontSide,
    vertexShader: `
      attribute vec2 uv1;
      varying vec2 vLightmapUv;
      void main() {
        vLightmapUv = uv1;
        gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0);
      }`,
    fragmentShader: `
      uniform sampler2D lightmaps[GROUPS];
      uniform float weights[GROUPS];
      uniform float scale;
      varying vec2 vLightmapUv;
      void main() {
        vec3 light = vec3(0.0);
        ${textures.map((_, i) => `light += weights[${i}] * texture2D(lightmaps[${i}], vLightmapUv).rgb;`).join('\n')}
        gl_FragColor = vec4(clamp(light * scale, 0.0, 1.0), 1.0);
        #include <colorspace_fragment>
      }`,
  });
}

function setUpCamera(camera, box) {
  const v = config.view;
  camera.position.set(...v.position);
  camera.up.set(...v.up);
  const size = box.getSize(new THREE.Vector3()).length();
  camera.near = Math.max(1e-4, size * 1e-3);
  camera.far = size * 100;
  const direction = new THREE.Vector3(...v.direction).normalize();
  // Orbit about the point straight ahead at the distance of the scene's centre.
  const centre = box.getCenter(new THREE.Vector3());
  const distance = Math.max(camera.near * 10, centre.clone().sub(camera.position).dot(direction));
  const target = camera.position.clone().addScaledVector(direction, distance);
  camera.lookAt(target);
  return target;
}

function fit(renderer, camera) {
  const w = window.innerWidth, h = window.innerHeight;
  renderer.setSize(w, h, false);
  const tanV = Math.tan((config.view.vertical_deg * Math.PI) / 360);
  const tanH = Math.tan((config.view.horizontal_deg * Math.PI) / 360);
  // Keep the whole of rad-shade's view in sight whatever the window's shape.
  const vertical = Math.max(tanV, tanH * (h / w));
  camera.fov = (2 * Math.atan(vertical) * 180) / Math.PI;
  camera.aspect = w / h;
  camera.updateProjectionMatrix();
}

function addSlider(panel, label, value, max, onInput) {
  const row = document.createElement('label');
  const text = document.createElement('span');
  const input = document.createElement('input');
  const shown = document.createElement('output');
  Object.assign(input, { type: 'range', min: 0, max, step: 0.01, value });
  input.dataset.name = label;
  text.textContent = label;
  shown.textContent = Number(value).toFixed(2);
  input.addEventListener('input', () => {
    shown.textContent = Number(input.value).toFixed(2);
    onInput(Number(input.value));
  });
  row.append(text, input, shown);
  panel.append(row);
  return input;
}

async function main() {
  const renderer = new THREE.WebGLRenderer({ canvas: document.getElementById('view'), antialias: true });
  renderer.outputColorSpace = THREE.SRGBColorSpace;
  renderer.toneMapping = THREE.NoToneMapping;
  const scene = new THREE.Scene();
  const gltf = await new GLTFLoader().parseAsync(decodeBase64(document.getElementById('radiosity-glb').textContent), '');
  scene.add(gltf.scene);
  const extras = gltf.parser.json.asset.extras.radiosity;
  const groups = extras.light_group_lightmaps ?? [];
  const state = { exposure: config.exposure, weights: Object.fromEntries(groups.map((g) => [g.name, 1])) };
  const materials = [];
  if (groups.length > 0) {
    const textures = await Promise.all(groups.map((g) => gltf.parser.getDependency('texture', g.texture)));
    for (const t of textures) {
      t.colorSpace = THREE.SRGBColorSpace;
      t.channel = 1;
    }
    gltf.scene.traverse((node) => {
      if (!node.isMesh) return;
      node.material = mixingMaterial(textures, node.material.side === THREE.DoubleSide);
      materials.push(node.material);
    });
  } else if (extras.lightmap_texture !== undefined) {
    // A glb for engines (rad-bake --engine): the scene's own materials lit by the irradiance
    // atlas in three.js's light-map slot on the second UV set. MeshStandardMaterial takes a
    // light map as irradiance and divides by pi (Lambert), hence the intensity pi.
    const lightMap = await gltf.parser.getDependency('texture', extras.lightmap_texture);
    lightMap.colorSpace = THREE.SRGBColorSpace;
    lightMap.channel = 1;
    gltf.scene.traverse((node) => {
      if (!node.isMesh) return;
      Object.assign(node.material, { lightMap, lightMapIntensity: Math.PI, envMap: null });
      node.material.needsUpdate = true;
      materials.push(node.material);
    });
  } else {
    gltf.scene.traverse((node) => node.isMesh && materials.push(node.material));
  }
  const camera = new THREE.PerspectiveCamera();
  const box = new THREE.Box3().setFromObject(gltf.scene);
  const target = setUpCamera(camera, box);
  const controls = new OrbitControls(camera, renderer.domElement);
  controls.target.copy(target);
  controls.update();

  const render = () => {
    const scale = state.exposure / extras.exposure;
    for (const m of materials) {
      if (m.isShaderMaterial) {
        m.uniforms.scale.value = scale;
        m.uniforms.weights.value = groups.map((g) => state.weights[g.name]);
      } else if (m.lightMap && !m.map) {
        if (m.baseColour === undefined) m.baseColour = { colour: m.color.clone(), emissive: m.emissive.clone() };
        m.lightMapIntensity = Math.PI * scale;
        m.emissive.copy(m.baseColour.emissive).multiplyScalar(scale);
      } else {
        m.color.setScalar(scale);
      }
    }
    renderer.render(scene, camera);
  };
  fit(renderer, camera);
  window.addEventListener('resize', () => { fit(renderer, camera); render(); });
  controls.addEventListener('change', render);

  const panel = document.getElementById('panel');
  addSlider(panel, 'exposure', state.exposure, state.exposure * 4, (v) => { state.exposure = v; render(); });
  for (const g of groups) addSlider(panel, g.name, 1, 4, (v) => { state.weights[g.name] = v; render(); });

  // For scripts (the browser test): set weights and exposure, read the pixels of a fresh frame.
  window.radiosity = {
    groups: groups.map((g) => g.name),
    set(settings) {
      if (settings.exposure !== undefined) state.exposure = settings.exposure;
      Object.assign(state.weights, settings.weights ?? {});
      for (const input of panel.querySelectorAll('input')) {
        const name = input.dataset.name;
        input.value = name === 'exposure' ? state.exposure : state.weights[name];
        input.nextSibling.textContent = Number(input.value).toFixed(2);
      }
      render();
    },
    pixels() {
      render();
      const gl = renderer.getContext();
      const w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
      const data = new Uint8Array(w * h * 4);
      gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, data);
      return { width: w, height: h, rgba: Array.from(data) }; // bottom row first
    },
  };
  render();
  document.body.dataset.ready = 'true';
}

main().catch((error) => {
  document.getElementById('panel').textContent = `Cannot show the scene: ${error.message}`;
  document.body.dataset.error = String(error.stack ?? error);
});
