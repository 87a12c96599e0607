// quadcover HTML report viewer: interactive 3D views of the meshes embedded in the page (three.js, inlined).
// Data: the JSON script element #qc-data holds {"meshes": [{name, positions, triangles, uv, edges, seams,
// branch_points, decimated}]}
// (this file is inlined into a script element: it must never contain a closing script tag)
//   positions  flat [x, y, z, ...]; triangles flat vertex indices; uv (optional) flat [u, v] per triangle corner
//   (3 per triangle, in grid units); edges (optional) flat vertex index pairs drawn as a wireframe; seams flat
//   vertex index pairs drawn in orange; branch_points [{vertex, quarter_index}] drawn as dots (+1 blue, -1 red,
//   +2 cyan, -2 magenta, others grey); decimated (optional) {faces, original_faces, method, cell_size}.
// Each mesh gets a canvas element of class qc-view with data-mesh="k". Drag rotates, the wheel zooms, double-click resets.
// After the first frame every canvas gets data-nonblank = number of pixels differing from the background, and
// #qc-status says "ok" (or the error), so headless browsers can check the page.
const status = document.getElementById('qc-status');
function fail(message) {
  status.textContent = 'error: ' + message;
  status.dataset.state = 'error';
}
window.addEventListener('error', (e) => fail(e.message));
window.addEventListener('unhandledrejection', (e) => fail(String(e.reason)));

const source = document.getElementById('qc-three').textContent;
const THREE = await import(URL.createObjectURL(new Blob([source], { type: 'text/javascript' })));
const data = JSON.parse(document.getElementById('qc-data').textContent);
const background = 0xf3f4f6;

function checkerTexture() {
  // 2×2 texels: one texel per unit square of the parameterization (uv are scaled by ½ below).
  const light = [236, 236, 228, 255], dark = [70, 125, 200, 255];
  const pixels = new Uint8Array([...light, ...dark, ...dark, ...light]);
  const tex = new THREE.DataTexture(pixels, 2, 2, THREE.RGBAFormat);
  tex.wrapS = tex.wrapT = THREE.RepeatWrapping;
  tex.magFilter = THREE.NearestFilter;
  tex.minFilter = THREE.LinearMipmapLinearFilter;
  tex.generateMipmaps = true;
  tex.colorSpace = THREE.SRGBColorSpace;
  tex.needsUpdate = true;
  return tex;
}

function buildObject(mesh) {
  const group = new THREE.Group();
  const P = mesh.positions, T = mesh.triangles;
  const geometry = new THREE.BufferGeometry();
  if (mesh.uv && mesh.uv.length === (T.length / 3) * 6) {
    // Per-corner UVs: unshared vertices so seams can jump.
    const pos = new Float32Array(T.length * 3), uv = new Float32Array(T.length * 2);
    for (let c = 0; c < T.length; ++c) {
      for (let d = 0; d < 3; ++d) pos[3 * c + d] = P[3 * T[c] + d];
      uv[2 * c] = mesh.uv[2 * c] / 2;
      uv[2 * c + 1] = mesh.uv[2 * c + 1] / 2;
    }
    geometry.setAttribute('position', new THREE.BufferAttribute(pos, 3));
    geometry.setAttribute('uv', new THREE.BufferAttribute(uv, 2));
  } else {
    geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(P), 3));
    geometry.setIndex(Array.from(T));
  }
  geometry.computeVertexNormals();
  const textured = geometry.getAttribute('uv') !== undefined;
  const material = new THREE.MeshLambertMaterial({
    color: textured ? 0xffffff : 0xdcdcd4,
    map: textured ? checkerTexture() : null,
    side: THREE.DoubleSide,
    polygonOffset: true,
    polygonOffsetFactor: 1,
    polygonOffsetUnits: 1,
  });
  group.add(new THREE.Mesh(geometry, material));
  if (mesh.edges && mesh.edges.length) {
    const E = mesh.edges, pos = new Float32Array(E.length * 3);
    for (let i = 0; i < E.length; ++i) for (let d = 0; d < 3; ++d) pos[3 * i + d] = P[3 * E[i] + d];
    const lines = new THREE.BufferGeometry();
    lines.setAttribute('position', new THREE.BufferAttribute(pos, 3));
    group.add(new THREE.LineSegments(lines, new THREE.LineBasicMaterial({ color: 0x1a1a22 })));
  }
  if (mesh.seams && mesh.seams.length) {
    const S = mesh.seams, pos = new Float32Array(S.length * 3);
    for (let i = 0; i < S.length; ++i) for (let d = 0; d < 3; ++d) pos[3 * i + d] = P[3 * S[i] + d];
    const lines = new THREE.BufferGeometry();
    lines.setAttribute('position', new THREE.BufferAttribute(pos, 3));
    group.add(new THREE.LineSegments(lines, new THREE.LineBasicMaterial({ color: 0xe6730d })));
  }
  if (mesh.branch_points && mesh.branch_points.length) {
    const B = mesh.branch_points, pos = new Float32Array(B.length * 3), col = new Float32Array(B.length * 3);
    const colours = { 1: [0.1, 0.3, 0.95], '-1': [0.9, 0.1, 0.1], 2: [0.0, 0.75, 0.85], '-2': [0.8, 0.1, 0.8] };
    B.forEach((b, i) => {
      for (let d = 0; d < 3; ++d) pos[3 * i + d] = P[3 * b.vertex + d];
      col.set(colours[b.quarter_index] || [0.3, 0.3, 0.3], 3 * i);
    });
    const points = new THREE.BufferGeometry();
    points.setAttribute('position', new THREE.BufferAttribute(pos, 3));
    points.setAttribute('color', new THREE.BufferAttribute(col, 3));
    group.add(new THREE.Points(points, new THREE.PointsMaterial({ size: 9, sizeAttenuation: false, vertexColors: true })));
  }
  geometry.computeBoundingSphere();
  return { group, sphere: geometry.boundingSphere };
}

function countNonBackground(gl, width, height) {
  const pixels = new Uint8Array(width * height * 4);
  gl.readPixels(0, 0, width, height, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
  const br = (background >> 16) & 255, bg = (background >> 8) & 255, bb = background & 255;
  let n = 0;
  for (let i = 0; i < pixels.length; i += 4)
    if (Math.abs(pixels[i] - br) + Math.abs(pixels[i + 1] - bg) + Math.abs(pixels[i + 2] - bb) > 24) ++n;
  return n;
}

function setupView(canvas, mesh) {
  const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(1);
  renderer.setSize(canvas.width, canvas.height, false);
  renderer.setClearColor(background);
  const scene = new THREE.Scene();
  const { group, sphere } = buildObject(mesh);
  group.position.copy(sphere.center).multiplyScalar(-1);
  const pivot = new THREE.Group();
  pivot.add(group);
  scene.add(pivot);
  scene.add(new THREE.AmbientLight(0xffffff, 1.2));
  const camera = new THREE.PerspectiveCamera(35, canvas.width / canvas.height, sphere.radius / 50, sphere.radius * 50);
  const light = new THREE.DirectionalLight(0xffffff, 2.2);
  light.position.set(-0.4, 0.6, 1);
  camera.add(light);
  scene.add(camera);
  const fit = sphere.radius / Math.sin((35 / 2) * Math.PI / 180) * 1.05;
  const yaw0 = 0.5, pitch0 = 0.45;  // a three-quarter view from above
  let yaw = yaw0, pitch = pitch0, distance = fit;
  function draw() {
    pivot.rotation.set(pitch, yaw, 0, 'XYZ');
    camera.position.set(0, 0, distance);
    camera.lookAt(0, 0, 0);
    renderer.render(scene, camera);
  }
  let drag = null;
  canvas.addEventListener('pointerdown', (e) => { drag = { x: e.clientX, y: e.clientY }; canvas.setPointerCapture(e.pointerId); });
  canvas.addEventListener('pointerup', () => { drag = null; });
  canvas.addEventListener('pointermove', (e) => {
    if (!drag) return;
    yaw += (e.clientX - drag.x) * 0.01;
    pitch = Math.max(-1.55, Math.min(1.55, pitch + (e.clientY - drag.y) * 0.01));
    drag = { x: e.clientX, y: e.clientY };
    draw();
  });
  canvas.addEventListener('wheel', (e) => {
    e.preventDefault();
    distance = Math.max(fit * 0.1, Math.min(fit * 10, distance * Math.exp(e.deltaY * 0.001)));
    draw();
  }, { passive: false });
  canvas.addEventListener('dblclick', () => { yaw = yaw0; pitch = pitch0; distance = fit; draw(); });
  draw();
  canvas.dataset.nonblank = String(countNonBackground(renderer.getContext(), canvas.width, canvas.height));
}

for (const canvas of document.querySelectorAll('canvas.qc-view')) setupView(canvas, data.meshes[Number(canvas.dataset.mesh)]);
if (status.dataset.state !== 'error') {
  status.textContent = 'ok';
  status.dataset.state = 'ok';
}
