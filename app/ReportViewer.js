// The page of an HTML report (app/HtmlReport): the table and the 3D view,
// built from the JSON in #dfrecon-data with three.js (inlined before this).
(function () {
  'use strict';
  const dataElement = document.getElementById('dfrecon-data');
  const data = JSON.parse(dataElement.textContent);
  // The embedded text is most of the page (tens of MB for a whole atlas):
  // once parsed it is dropped from the document, so the page does not hold
  // it twice and a saved or dumped DOM stays small.
  dataElement.remove();
  document.title = data.title;
  document.getElementById('title').textContent = data.title;

  function bytes(text) {
    const raw = atob(text);
    const out = new Uint8Array(raw.length);
    for (let i = 0; i < raw.length; ++i) out[i] = raw.charCodeAt(i);
    return out.buffer;
  }
  function cell(value) {
    if (value === null || value === undefined) return '';
    if (typeof value === 'number' && !Number.isInteger(value)) return value.toPrecision(6);
    return String(value);
  }

  // The table: one row per result; a row whose name is a surface's gets
  // its colour and a box that shows or hides it.
  const meshes = {};
  const table = document.createElement('table');
  const head = table.insertRow();
  for (const column of data.columns) {
    const th = document.createElement('th');
    th.textContent = column;
    head.appendChild(th);
  }
  const surfaceNames = new Set(data.surfaces.map((s) => s.name));
  for (const row of data.rows) {
    const tr = table.insertRow();
    data.columns.forEach((column, k) => {
      const td = tr.insertCell();
      const text = cell(row[column]);
      if (k === 0 && surfaceNames.has(text)) {
        const box = document.createElement('input');
        box.type = 'checkbox';
        box.checked = true;
        box.onchange = () => { if (meshes[text]) { meshes[text].visible = box.checked; draw(); } };
        const s = data.surfaces.find((x) => x.name === text);
        td.append(box);
        // A surface coloured by its values has no one colour to show.
        if (!s.pointColours) {
          const swatch = document.createElement('span');
          swatch.className = 'swatch';
          swatch.style.background = 'rgb(' + s.colour.join(',') + ')';
          td.append(swatch);
        }
      }
      td.append(text);
    });
  }
  document.getElementById('table').appendChild(table);
  if (data.note) {
    const p = document.createElement('p');
    p.textContent = data.note;
    document.getElementById('table').appendChild(p);
  }
  if (data.valueName) {
    document.getElementById('legend').textContent = 'Colours: ' + data.valueName +
        ', blue (−' + data.valueScaleMm.toPrecision(3) + ') to white (0) to red (+' +
        data.valueScaleMm.toPrecision(3) + ').';
  }

  // The 3D view: patient coordinates (LPS, mm), head up (+z), seen from the
  // front (−y), a little from the patient's right (−x) and from above, so
  // that flat structures show their faces too.
  const view = document.getElementById('view');
  const note = document.getElementById('note');
  let renderer;
  try {
    renderer = new THREE.WebGLRenderer({antialias: true, preserveDrawingBuffer: true});
  } catch (error) {
    note.textContent = 'This browser has no WebGL: the table above holds every figure.';
    document.body.dataset.webgl = '0';
    document.body.dataset.surfaces = '0';
    return;
  }
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  view.appendChild(renderer.domElement);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0x20242a);
  const camera = new THREE.PerspectiveCamera(35, 1, 0.1, 1e5);
  camera.up.set(0, 0, 1);
  scene.add(new THREE.AmbientLight(0xffffff, 0.45));
  const light = new THREE.DirectionalLight(0xffffff, 0.75);
  camera.add(light);
  scene.add(camera);

  const box = new THREE.Box3();
  for (const s of data.surfaces) {
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(bytes(s.positions)), 3));
    geometry.setIndex(new THREE.BufferAttribute(new Uint32Array(bytes(s.triangles)), 1));
    geometry.computeVertexNormals();
    const options = {side: THREE.DoubleSide, shininess: 20};
    if (s.pointColours) {
      geometry.setAttribute('color', new THREE.BufferAttribute(new Uint8Array(bytes(s.pointColours)), 3, true));
      options.vertexColors = true;
    } else {
      options.color = new THREE.Color(s.colour[0] / 255, s.colour[1] / 255, s.colour[2] / 255);
    }
    s.positions = s.triangles = s.pointColours = undefined;  // decoded: the text can go
    const mesh = new THREE.Mesh(geometry, new THREE.MeshPhongMaterial(options));
    mesh.name = s.name;
    meshes[s.name] = mesh;
    scene.add(mesh);
    geometry.computeBoundingBox();
    box.union(geometry.boundingBox);
  }
  const centre = box.isEmpty() ? new THREE.Vector3() : box.getCenter(new THREE.Vector3());
  const radius = box.isEmpty() ? 100 : Math.max(1, box.getSize(new THREE.Vector3()).length() / 2);
  // The bounding sphere fits a 35° view at 3.2 radii; 4 leaves a margin and
  // room for a view narrower than it is high.
  const eye = new THREE.Vector3(-0.45, -1, 0.55).normalize().multiplyScalar(4 * radius);
  camera.position.copy(centre).add(eye);
  camera.near = radius / 100;
  camera.far = radius * 100;
  const controls = new THREE.OrbitControls(camera, renderer.domElement);
  controls.target.copy(centre);
  controls.addEventListener('change', draw);

  function resize() {
    const width = view.clientWidth, height = view.clientHeight;
    renderer.setSize(width, height);
    camera.aspect = width / Math.max(1, height);
    camera.updateProjectionMatrix();
    draw();
  }
  function draw() {
    renderer.render(scene, camera);
  }
  window.addEventListener('resize', resize);
  controls.update();
  resize();
  document.body.dataset.webgl = '1';
  document.body.dataset.surfaces = String(data.surfaces.length);
})();
