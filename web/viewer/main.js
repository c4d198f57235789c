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

// ---- Daylight (a page of a daylight solution): the sky of a date and time, as the chain's
// Sky::of_day makes it (a clear, partly cloudy or overcast day), or a weather file's hour as
// rad-bake computed it, weighting the components of the solution's basis (one texture array).
const DEG = Math.PI / 180;

// The sun at day of year `day` and `hour` (local standard time) by NOAA's general solar
// position formulas (within a few tenths of a degree; no refraction).
function sunPosition(site, day, hour) {
  const g = ((2 * Math.PI) / 365) * (day - 1 + (hour - 12) / 24);
  const eqtime = 229.18 * (0.000075 + 0.001868 * Math.cos(g) - 0.032077 * Math.sin(g) -
    0.014615 * Math.cos(2 * g) - 0.040849 * Math.sin(2 * g));
  const decl = 0.006918 - 0.399912 * Math.cos(g) + 0.070257 * Math.sin(g) - 0.006758 * Math.cos(2 * g) +
    0.000907 * Math.sin(2 * g) - 0.002697 * Math.cos(3 * g) + 0.00148 * Math.sin(3 * g);
  const minutes = hour * 60 + eqtime + 4 * site.longitude - 60 * site.time_zone;
  const ha = (minutes / 4 - 180) * DEG, lat = site.latitude * DEG;
  const cosZ = Math.sin(lat) * Math.sin(decl) + Math.cos(lat) * Math.cos(decl) * Math.cos(ha);
  const altitude = Math.asin(Math.max(-1, Math.min(1, cosZ)));
  const azimuth = Math.atan2(Math.sin(ha), Math.cos(ha) * Math.sin(lat) - Math.tan(decl) * Math.cos(lat)) + Math.PI;
  return { altitude, azimuth };
}

// Reinhart's sky patches (the chain's numbering: the ground, rows from the horizon up, each
// from north towards east, the zenith cap), each as 4 x 4 cells of equal solid angle.
function skyPatches(m) {
  const perRow = [30, 30, 24, 24, 18, 12, 6];
  const alpha = (Math.PI / 2) / (7 * m + 0.5);
  const patches = [null];
  const add = (a0, a1, z0, z1) => {
    const cells = [];
    for (let i = 0; i < 4; ++i) {
      const alt = Math.asin(Math.sin(a0) + ((Math.sin(a1) - Math.sin(a0)) * (i + 0.5)) / 4);
      for (let j = 0; j < 4; ++j) cells.push({ alt, az: z0 + ((z1 - z0) * (j + 0.5)) / 4 });
    }
    patches.push({ a0, a1, z0, z1, cells, omega: (Math.sin(a1) - Math.sin(a0)) * (z1 - z0) });
  };
  for (let row = 0; row < 7 * m; ++row) {
    const n = perRow[Math.floor(row / m)] * m, w = (2 * Math.PI) / n;
    for (let j = 0; j < n; ++j) add(row * alpha, (row + 1) * alpha, j * w - w / 2, j * w + w / 2);
  }
  add(Math.PI / 2 - alpha / 2, Math.PI / 2, 0, 2 * Math.PI);
  return { patches, alpha, perRow, m };
}

function patchOf(sky, alt, az) {
  const row = Math.floor(alt / sky.alpha);
  if (row >= 7 * sky.m) return sky.patches.length - 1;
  let first = 1;
  for (let r = 0; r < row; ++r) first += sky.perRow[Math.floor(r / sky.m)] * sky.m;
  const n = sky.perRow[Math.floor(row / sky.m)] * sky.m;
  const a = ((az % (2 * Math.PI)) + 2 * Math.PI) % (2 * Math.PI);
  return first + (Math.floor((a * n) / (2 * Math.PI) + 0.5) % n);
}

// Each sky patch's mean luminance (cd/m^2) under a day's sky with the sun `sun`: its CIE type
// scaled to A + B sin(a)^p lux on the horizontal (day.diffuse), the ground uniform; and the
// sun's beam, 127500 exp(-c / sin a) lux (c: day.extinction, 0 for none), as the luminance of
// the patch it is in (sunPatch, sunLuminance).
function daySkyLuminance(sky, sun, ground, day) {
  const out = new Array(sky.patches.length).fill(0);
  out.sunPatch = -1;
  out.sunLuminance = 0;
  if (sun.altitude <= 0) return out;
  const [a, b, c, d, e] = day.parameters;
  const gradation = (cosZ) => 1 + a * Math.exp(b / Math.max(cosZ, 1e-9));
  const indicatrix = (g) => 1 + c * (Math.exp(d * g) - Math.exp((d * Math.PI) / 2)) + e * Math.cos(g) ** 2;
  const zs = Math.PI / 2 - sun.altitude;
  const zenith = gradation(1) * indicatrix(zs);
  const relative = (alt, az) => {
    const cosG = Math.sin(alt) * Math.sin(sun.altitude) + Math.cos(alt) * Math.cos(sun.altitude) * Math.cos(az - sun.azimuth);
    return (gradation(Math.sin(alt)) * indicatrix(Math.acos(Math.max(-1, Math.min(1, cosG))))) / zenith;
  };
  let integral = 0;
  for (let p = 1; p < sky.patches.length; ++p) {
    const patch = sky.patches[p];
    let sum = 0;
    for (const cell of patch.cells) {
      const r = relative(cell.alt, cell.az);
      sum += r;
      integral += (r * Math.sin(cell.alt) * patch.omega) / patch.cells.length;
    }
    out[p] = sum / patch.cells.length;
  }
  const s = Math.sin(sun.altitude);
  const [A, B, power] = day.diffuse;
  const diffuse = A + B * (power === 0.5 ? Math.sqrt(s) : s ** power);
  const beam = day.extinction > 0 ? 127500 * Math.exp(-day.extinction / s) : 0;
  for (let p = 1; p < out.length; ++p) out[p] *= diffuse / integral;
  if (beam > 0) {
    out.sunPatch = patchOf(sky, sun.altitude, sun.azimuth);
    out.sunLuminance = beam / sky.patches[out.sunPatch].omega;
    out.beam = beam;
  }
  out[0] = (ground * (diffuse + beam * s)) / Math.PI;
  return out;
}

// The mean luminance of the sky above the horizon and of the ground below (cd/m^2), for
// what windows and openings show.
function skyAndGround(sky, luminance) {
  let seen = 0, omega = 0;
  for (let p = 1; p < sky.patches.length; ++p) {
    seen += luminance[p] * sky.patches[p].omega;
    omega += sky.patches[p].omega;
  }
  return [seen / omega, luminance[0]];
}

// A weather file's hour (rad-bake --epw) at day `day` and `hour`: the record of the hour ending
// at or after it (EPW's hour 1 is 00:00 to 01:00), as rad-shade --sky epw:FILE takes it; null
// when that hour is dark.
function weatherHour(weather, components, day, hour) {
  const ending = Math.min(24, Math.max(1, Math.ceil(hour - 1e-9)));
  const t = (Math.round(day) - 1) * 24 + ending - 1;
  let lo = 0, hi = weather.hours.length - 1;
  while (lo <= hi) {
    const mid = (lo + hi) >> 1;
    if (weather.hours[mid] === t) {
      return {
        weights: weather.weights.slice(mid * components, (mid + 1) * components),
        sunPatch: weather.sun_patch[mid],
        sunLuminance: weather.beam_luminance[mid],
        skyGround: weather.sky_ground_luminance[mid],
        sun: weather.sun[mid], // towards the sun (scene frame) and the beam's lux
      };
    }
    if (weather.hours[mid] < t) lo = mid + 1;
    else hi = mid - 1;
  }
  return null;
}

// Mixes the basis layers: sum of weight x (linear) texel plus a bias (the layers are signed,
// stored as 0.5 + 0.5 x value / scale), times the exposure; encoded to sRGB for display.
// The sun's beam is added sharp, as rad-shade --sky and rad-gather trace it: rho x the beam's
// irradiance x cos x what the panes on its way let through, where the sun's shadow map says
// the point sees the sun (`sun`: the maps and the beam, shared by every material).
function daylightMaterial(basis, count, doubleSided, rho, sun) {
  return new THREE.ShaderMaterial({
    glslVersion: THREE.GLSL3,
    defines: { COMPONENTS: count },
    uniforms: { basis: { value: basis }, weights: { value: new Array(count).fill(0) }, bias: { value: 0 }, scale: { value: 1 },
      rho: { value: new THREE.Vector3(...rho) }, ...sun.uniforms },
    side: doubleSided ? THREE.DoubleSide : THREE.FrontSide,
    vertexShader: `
      in vec2 uv1;
      out vec2 vLightmapUv;
      in vec3 corner0, corner1, corner2, barycentric;
      out vec3 vWorld, vBarycentric;
      flat out vec3 vNormal, vCorner0, vCorner1, vCorner2; // the triangle's (prepareTriangles)
      void main() {
        vLightmapUv = uv1;
        vec4 world = modelMatrix * vec4(position, 1.0);
        vWorld = world.xyz;
        vNormal = normalize(mat3(modelMatrix) * normal);
        vCorner0 = (modelMatrix * vec4(corner0, 1.0)).xyz;
        vCorner1 = (modelMatrix * vec4(corner1, 1.0)).xyz;
        vCorner2 = (modelMatrix * vec4(corner2, 1.0)).xyz;
        vBarycentric = barycentric;
        gl_Position = projectionMatrix * viewMatrix * world;
      }`,
    fragmentShader: `
      layout(location = 0) out highp vec4 pc_fragColor;
      #define gl_FragColor pc_fragColor
      precision highp sampler2DArray;
      uniform sampler2DArray basis;
      uniform float weights[COMPONENTS];
      uniform float bias;
      uniform float scale;
      uniform vec3 rho;
      uniform vec3 sunDirection;
      uniform float sunIrradiance;
      uniform mat4 sunMatrix;
      uniform float sunTexel;
      uniform sampler2D sunDepth;
      uniform sampler2D sunGlass;
      in vec2 vLightmapUv;
      in vec3 vWorld, vBarycentric;
      flat in vec3 vNormal, vCorner0, vCorner1, vCorner2;
      // The beam's irradiance (W/m^2) at this point: 0 in the shadow of an opaque surface,
      // times the transmittance of a pane nearer the sun.
      vec3 toMap(vec3 point) {
        vec4 p = sunMatrix * vec4(point, 1.0);
        return p.xyz / p.w * 0.5 + 0.5;
      }
      float beam() {
        if (!(sunIrradiance > 0.0)) return 0.0;
        vec3 n = vNormal;
        if (dot(n, cameraPosition - vWorld) < 0.0) n = -n;
        float c = dot(n, sunDirection);
        if (c <= 0.0) return 0.0;
        // The point tested: on the triangle (see prepareTriangles), a texel off its surface and
        // a texel away from the sun (so that a wall the beam grazes still shadows its foot).
        vec3 b = max(vBarycentric, vec3(0.0));
        b /= max(b.x + b.y + b.z, 1e-6);
        vec3 point = b.x * vCorner0 + b.y * vCorner1 + b.z * vCorner2 + (n - sunDirection) * sunTexel;
        vec3 q = toMap(point);
        if (any(lessThan(q, vec3(0.0))) || any(greaterThan(q, vec3(1.0)))) return 0.0;
        // The surface's own depth beside the point, in the map: its plane seen from the sun
        // (two steps along it), so that a texel of the map is compared with the surface where
        // that texel is, not where the point is (a surface the beam grazes changes depth fast).
        vec3 t1 = normalize(abs(n.y) < 0.9 ? cross(n, vec3(0.0, 1.0, 0.0)) : cross(n, vec3(1.0, 0.0, 0.0)));
        vec3 t2 = cross(n, t1);
        vec3 q1 = toMap(point + t1 * sunTexel) - q, q2 = toMap(point + t2 * sunTexel) - q;
        float det = q1.x * q2.y - q1.y * q2.x;
        if (abs(det) < 1e-12) return 0.0;
        float texel = 1.0 / float(textureSize(sunDepth, 0).x);
        // What the comparison forgives: the surface's depth change over a texel, and two
        // texels' worth of depth (the map's and the plane's rounding).
        float slack = abs(q1.z) + abs(q2.z) + 2.0 * abs(toMap(point + sunDirection * sunTexel).z - q.z);
        // Four taps a texel and a half apart (a shadow's edge a few millimetres wide, partly
        // lit across it); each takes the nearest occluder of the texels around it: a wall the
        // beam grazes is a sliver in the map, and a point at its foot would otherwise fall just
        // beside it, where nothing is drawn.
        float seen = 0.0;
        for (int k = 0; k < 4; ++k) {
          vec2 at = q.xy + vec2(k % 2 == 0 ? -0.75 : 0.75, k < 2 ? -0.75 : 0.75) * texel;
          bool lit = true;
          for (int j = 0; j < 9 && lit; ++j) {
            vec2 d = at + vec2(j % 3 - 1, j / 3 - 1) * texel - q.xy;
            // Where the surface's plane is at that texel: d = a q1.xy + e q2.xy.
            float a = (d.x * q2.y - d.y * q2.x) / det, e = (q1.x * d.y - q1.y * d.x) / det;
            float own = q.z + a * q1.z + e * q2.z;
            lit = textureLod(sunDepth, q.xy + d, 0.0).r >= own - slack;
          }
          if (!lit) continue;
          vec4 glass = textureLod(sunGlass, at, 0.0);
          seen += glass.y < q.z ? glass.x : 1.0;
        }
        return sunIrradiance * c * seen * 0.25;
      }
      void main() {
        vec3 light = vec3(bias);
        for (int k = 0; k < COMPONENTS; ++k) light += weights[k] * textureLod(basis, vec3(vLightmapUv, float(k)), 0.0).rgb;
        light += rho * beam();
        gl_FragColor = vec4(clamp(light * scale, 0.0, 1.0), 1.0);
        #include <colorspace_fragment>
      }`,
  });
}

// Each triangle its own vertices, its plane's normal (the beam's cosine and the shadow test's
// offset need the surface's true normal, not one averaged over a corner), and at each vertex
// the triangle's three corners and the vertex's barycentric coordinates: with multisampling a
// pixel on a triangle's edge is shaded at its centre, which may lie beyond the edge (a
// floor's point past the wall, outside in the sun); the shader takes the nearest point of the
// triangle instead.
function prepareTriangles(node) {
  if (node.geometry.index) node.geometry = node.geometry.toNonIndexed();
  const g = node.geometry;
  g.deleteAttribute('normal');
  g.computeVertexNormals();
  const position = g.getAttribute('position');
  const count = position.count;
  const corners = [0, 1, 2].map(() => new Float32Array(3 * count));
  const barycentric = new Float32Array(3 * count);
  for (let v = 0; v < count; ++v) {
    const first = v - (v % 3);
    for (let k = 0; k < 3; ++k)
      corners[k].set([position.getX(first + k), position.getY(first + k), position.getZ(first + k)], 3 * v);
    barycentric[3 * v + (v % 3)] = 1;
  }
  corners.forEach((c, k) => g.setAttribute(`corner${k}`, new THREE.BufferAttribute(c, 3)));
  g.setAttribute('barycentric', new THREE.BufferAttribute(barycentric, 3));
}

// ---- The sun's maps: what the sun sees of the scene, drawn from its direction (an
// orthographic camera over the scene's bounds): the depth of the nearest opaque surface, and
// of the nearest pane with what it lets through at the angle the beam meets it.
const SUN_MAP = 2048;
function sunMaps(box) {
  const size = Math.max(1e-6, box.getSize(new THREE.Vector3()).length());
  const camera = new THREE.OrthographicCamera(-size / 2, size / 2, size / 2, -size / 2, size * 0.01, size * 3);
  const options = { minFilter: THREE.NearestFilter, magFilter: THREE.NearestFilter, generateMipmaps: false };
  const depth = new THREE.WebGLRenderTarget(SUN_MAP, SUN_MAP, { ...options, depthTexture: new THREE.DepthTexture(SUN_MAP, SUN_MAP) });
  const glass = new THREE.WebGLRenderTarget(SUN_MAP, SUN_MAP, { ...options, type: THREE.FloatType });
  return {
    camera, depth, glass, centre: box.getCenter(new THREE.Vector3()), size,
    opaque: opaqueMapMaterial(),
    uniforms: {
      sunDirection: { value: new THREE.Vector3(0, 1, 0) },
      sunIrradiance: { value: 0 },
      sunMatrix: { value: new THREE.Matrix4() },
      sunTexel: { value: size / SUN_MAP },
      sunDepth: { value: depth.depthTexture },
      sunGlass: { value: glass.texture },
    },
  };
}

// The opaque surfaces' depth from the sun, both sides (the walls face in, the sun sees their
// backs), each texel the nearest its surface comes within it (a polygon offset by the
// surface's slope towards the sun): a wall the beam grazes is seen edge on, its depth changes
// by many centimetres across a texel, and the texel's centre alone would leave the foot of it
// in the sun at random.
function opaqueMapMaterial() {
  return new THREE.MeshBasicMaterial({ side: THREE.DoubleSide, colorWrite: false, polygonOffset: true,
    polygonOffsetFactor: -1.5, polygonOffsetUnits: -1 });
}

// What a pane lets through of the beam (its luminous share by cos, 33 steps; rad-bake's
// table) and its depth from the sun, into the glass map.
function paneMapMaterial(table, sun) {
  return new THREE.ShaderMaterial({
    uniforms: { table: { value: table }, sunDirection: sun.uniforms.sunDirection },
    side: THREE.DoubleSide,
    vertexShader: `
      varying vec3 vNormal;
      void main() {
        vNormal = normalize(mat3(modelMatrix) * normal);
        gl_Position = projectionMatrix * viewMatrix * modelMatrix * vec4(position, 1.0);
      }`,
    fragmentShader: `
      uniform float table[33];
      uniform vec3 sunDirection;
      varying vec3 vNormal;
      void main() {
        vec3 n = normalize(vNormal);
        float x = clamp(abs(dot(n, sunDirection)), 0.0, 1.0) * 32.0;
        int k = int(min(floor(x), 31.0));
        float t = mix(table[k], table[k + 1], x - float(k));
        gl_FragColor = vec4(t, gl_FragCoord.z, 0.0, 1.0);
      }`,
  });
}

// Draws the sun's maps for the beam towards `direction` (scene frame, unit) of `irradiance`
// W/m^2 (0: no beam, nothing drawn).
function drawSunMaps(renderer, scene, sun, meshes, panes, direction, irradiance) {
  sun.uniforms.sunIrradiance.value = irradiance;
  if (!(irradiance > 0)) return;
  sun.uniforms.sunDirection.value.copy(direction);
  const camera = sun.camera;
  camera.position.copy(sun.centre).addScaledVector(direction, sun.size * 1.5);
  camera.up.set(0, 1, 0);
  if (Math.abs(direction.y) > 0.99) camera.up.set(0, 0, 1);
  camera.lookAt(sun.centre);
  camera.updateMatrixWorld();
  camera.updateProjectionMatrix();
  sun.uniforms.sunMatrix.value.multiplyMatrices(camera.projectionMatrix, camera.matrixWorldInverse);
  const shown = new Map(meshes.map((m) => [m, m.visible]));
  const colour = renderer.getClearColor(new THREE.Color()), alpha = renderer.getClearAlpha();
  // The opaque surfaces' depth (opaqueMapMaterial).
  for (const m of meshes) m.visible = !panes.includes(m);
  scene.overrideMaterial = sun.opaque;
  renderer.setRenderTarget(sun.depth);
  renderer.clear();
  renderer.render(scene, camera);
  scene.overrideMaterial = null;
  // The panes: what they let through, and their depth (none: 1 and the far plane).
  for (const m of meshes) m.visible = panes.includes(m);
  const materials = panes.map((p) => p.material);
  panes.forEach((p) => { p.material = p.userData.sunMap; });
  renderer.setRenderTarget(sun.glass);
  renderer.setClearColor(new THREE.Color(1, 1, 0), 1);
  renderer.clear();
  renderer.render(scene, camera);
  panes.forEach((p, k) => { p.material = materials[k]; });
  renderer.setRenderTarget(null);
  renderer.setClearColor(colour, alpha);
  for (const [m, visible] of shown) m.visible = visible;
}

// A pane of glass: what is outside along the line of sight (the sky above the horizon, the
// ground below: their mean luminances as display values, pi L / 179 x exposure),
// times what the pane lets through; drawn as its own colour, not blended, so that the
// product is taken on linear values before the sRGB encoding. The little it reflects is left
// out.
function glassMaterial(through, outside) {
  return new THREE.ShaderMaterial({
    uniforms: { sky: outside.sky, ground: outside.ground, through: { value: through } },
    side: THREE.DoubleSide,
    vertexShader: `
      varying vec3 vWorld;
      void main() {
        vec4 world = modelMatrix * vec4(position, 1.0);
        vWorld = world.xyz;
        gl_Position = projectionMatrix * viewMatrix * world;
      }`,
    fragmentShader: `
      uniform vec3 sky;
      uniform vec3 ground;
      uniform float through;
      varying vec3 vWorld;
      void main() {
        vec3 outside = (vWorld - cameraPosition).y >= 0.0 ? sky : ground;
        gl_FragColor = vec4(clamp(through * outside, 0.0, 1.0), 1.0);
        #include <colorspace_fragment>
      }`,
  });
}

// The basis layers (PNG textures of the glb) as one texture array, linear.
async function basisTexture(parser, groups) {
  const textures = await Promise.all(groups.map((g) => parser.getDependency('texture', g.texture)));
  const { width, height } = textures[0].image;
  const data = new Uint8Array(width * height * 4 * textures.length);
  const canvas = document.createElement('canvas');
  Object.assign(canvas, { width, height });
  const context = canvas.getContext('2d', { willReadFrequently: true, colorSpace: 'srgb' });
  textures.forEach((t, k) => {
    context.clearRect(0, 0, width, height);
    context.drawImage(t.image, 0, 0);
    data.set(context.getImageData(0, 0, width, height).data, k * width * height * 4);
  });
  const array = new THREE.DataArrayTexture(data, width, height, textures.length);
  Object.assign(array, { format: THREE.RGBAFormat, type: THREE.UnsignedByteType, minFilter: THREE.LinearFilter,
    magFilter: THREE.LinearFilter, colorSpace: THREE.NoColorSpace, generateMipmaps: false });
  array.needsUpdate = true;
  return array;
}

const MONTHS = ['Jan', 'Feb', 'Mar', 'Apr', 'May', 'Jun', 'Jul', 'Aug', 'Sep', 'Oct', 'Nov', 'Dec'];
function dateText(day, hour) {
  const lengths = [31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31];
  let month = 0, rest = Math.round(day);
  while (rest > lengths[month]) rest -= lengths[month++];
  const h = Math.floor(hour), m = Math.round((hour - h) * 60);
  return `${rest} ${MONTHS[month]} ${String(h).padStart(2, '0')}:${String(m).padStart(2, '0')}`;
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

function addSlider(panel, label, value, max, onInput, min = 0, step = 0.01) {
  const row = document.createElement('label');
  const text = document.createElement('span');
  const input = document.createElement('input');
  const shown = document.createElement('output');
  Object.assign(input, { type: 'range', min, max, step, value });
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
  const daylight = extras.daylight;
  const groups = daylight ? [] : extras.light_group_lightmaps ?? [];
  const state = { exposure: config.exposure, weights: Object.fromEntries(groups.map((g) => [g.name, 1])), day: 80, hour: 12, sky: 0 };
  const materials = [];
  let sky = null, sun = null;
  // What the windows show outside (not drawn around the room: cracks between its surfaces
  // would show it).
  const outside = { sky: { value: new THREE.Color(0, 0, 0) }, ground: { value: new THREE.Color(0, 0, 0) } };
  const panes = [], meshes = [];
  if (daylight) {
    const basis = await basisTexture(gltf.parser, extras.light_group_lightmaps);
    sky = skyPatches(daylight.subdivisions);
    gltf.scene.traverse((node) => node.isMesh && meshes.push(node));
    const bounds = new THREE.Box3().setFromObject(gltf.scene);
    sun = sunMaps(bounds);
    for (const node of meshes) {
      prepareTriangles(node);
      // Glass shows what is behind it, the sky through the window, dimmed by what it lets
      // through (its lightmap is the little it reflects: drawn over it).
      const t = node.material.userData?.transmittance;
      const through = t ? (t[0] + t[1] + t[2]) / 3 : 0;
      if (through > 0) {
        const table = daylight.panes?.[node.material.name] ?? new Array(33).fill(through);
        node.userData.sunMap = paneMapMaterial(table, sun);
        node.material = glassMaterial(through, outside);
        panes.push(node);
        continue;
      }
      node.material = daylightMaterial(basis, 2 * (daylight.components.length + daylight.sun_patches.length),
        node.material.side === THREE.DoubleSide, node.material.userData?.reflectance ?? [0, 0, 0], sun);
      materials.push(node.material);
    }
  } else if (groups.length > 0) {
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

  // The sky at the state's day and hour: the components' weights, the sun's patch and beam
  // luminance, and the sky's and the ground's mean luminance.
  const skyOfNow = () => {
    const count = daylight.components.length;
    if (state.sky === 'weather') {
      return weatherHour(daylight.weather, count, state.day, state.hour) ??
        { weights: new Array(count).fill(0), sunPatch: -1, sunLuminance: 0, skyGround: [0, 0], sun: [0, 1, 0, 0] };
    }
    const day = daylight.days[state.sky];
    const position = sunPosition(daylight, state.day, state.hour);
    const luminance = daySkyLuminance(sky, position, daylight.ground, day);
    const weights = daylight.components.map((c) => {
      let w = 0;
      for (let k = 0; k < luminance.length; ++k) w += c.weights[k] * luminance[k];
      return w;
    });
    // Towards the sun in the scene: north is -Z turned `north` degrees towards +X.
    const n = daylight.north * DEG, ca = Math.cos(position.altitude);
    const north = [Math.sin(n), 0, -Math.cos(n)], east = [Math.cos(n), 0, Math.sin(n)];
    const d = [0, 1, 2].map((i) => north[i] * ca * Math.cos(position.azimuth) + east[i] * ca * Math.sin(position.azimuth));
    d[1] += Math.sin(position.altitude);
    return { weights, sunPatch: luminance.sunPatch, sunLuminance: luminance.sunLuminance, skyGround: skyAndGround(sky, luminance),
      sun: [...d, luminance.beam ?? 0] };
  };
  let sunDrawn = null;

  const render = () => {
    const scale = state.exposure / extras.exposure;
    let daylightWeights = null, bias = 0;
    if (daylight) {
      const hour = skyOfNow();
      // The sky through the basis, the sun through its own patch's group (a layer each).
      // Each component (and each sun patch's group) in two layers, the high and the low
      // byte of 16 bits.
      daylightWeights = daylight.components.flatMap((c, k) => {
        const w = hour.weights[k];
        bias -= w * c.scale;
        return [(2 * w * c.scale * 65280) / 65535, (2 * w * c.scale * 255) / 65535];
      });
      for (const sunLayer of daylight.sun_patches) {
        const w = sunLayer.patch === hour.sunPatch ? hour.sunLuminance / 179 : 0;
        bias -= w * sunLayer.scale;
        daylightWeights.push((2 * w * sunLayer.scale * 65280) / 65535, (2 * w * sunLayer.scale * 255) / 65535);
      }
      // The beam's maps, drawn again when the sun moves.
      const key = hour.sun.join(',');
      if (key !== sunDrawn) {
        drawSunMaps(renderer, scene, sun, meshes, panes, new THREE.Vector3(...hour.sun.slice(0, 3)).normalize(), hour.sun[3] / 179);
        sunDrawn = key;
      }
      const display = (l) => (Math.PI * l * state.exposure) / 179;
      outside.sky.value.setScalar(display(hour.skyGround[0]));
      outside.ground.value.setScalar(display(hour.skyGround[1]));
    }
    for (const m of materials) {
      if (daylightWeights) {
        m.uniforms.scale.value = state.exposure;
        m.uniforms.weights.value = daylightWeights;
        m.uniforms.bias.value = bias;
      } else if (m.isShaderMaterial) {
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
  const when = document.createElement('div');
  const skyName = () => (state.sky === 'weather' ? `weather file ${daylight.weather.place}` : daylight.days[state.sky].name);
  const showWhen = () => { when.textContent = daylight ? `${dateText(state.day, state.hour)}, ${skyName()}` : ''; };
  let skyMenu = null;
  if (daylight) {
    addSlider(panel, 'day', state.day, 365, (v) => { state.day = v; showWhen(); render(); }, 1, 1);
    addSlider(panel, 'hour', state.hour, 24, (v) => { state.hour = v; showWhen(); render(); }, 0, 0.25);
    skyMenu = document.createElement('select');
    daylight.days.forEach((d, k) => skyMenu.append(new Option(d.name, String(k))));
    if (daylight.weather) skyMenu.append(new Option(`weather file: ${daylight.weather.place} (Perez, hourly)`, 'weather'));
    skyMenu.addEventListener('change', () => {
      state.sky = skyMenu.value === 'weather' ? 'weather' : Number(skyMenu.value);
      showWhen();
      render();
    });
    const row = document.createElement('label');
    const text = document.createElement('span');
    text.textContent = 'sky';
    row.append(text, skyMenu);
    panel.append(row, when);
    showWhen();
  }

  // For scripts (the browser test): set weights and exposure, read the pixels of a fresh frame.
  window.radiosity = {
    groups: groups.map((g) => g.name),
    // The window panes and what they show outside (display values, linear).
    panes: () => panes.map((p) => p.material.uniforms.through.value),
    outside: () => (daylight ? [outside.sky.value.r, outside.ground.value.r] : null),
    set(settings) {
      if (settings.exposure !== undefined) state.exposure = settings.exposure;
      if (settings.day !== undefined) state.day = settings.day;
      if (settings.hour !== undefined) state.hour = settings.hour;
      if (settings.sky !== undefined) {
        if (settings.sky === 'weather' && !daylight?.weather) throw new Error('the page has no weather file');
        state.sky = settings.sky === 'weather' ? 'weather' : daylight.days.findIndex((d) => d.name.startsWith(settings.sky.replace('-', ' ')));
        if (state.sky === -1) throw new Error(`no sky named ${settings.sky}`);
        skyMenu.value = String(state.sky);
      }
      showWhen();
      Object.assign(state.weights, settings.weights ?? {});
      for (const input of panel.querySelectorAll('input')) {
        const name = input.dataset.name;
        input.value = name === 'exposure' || name === 'day' || name === 'hour' ? state[name] : state.weights[name];
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
