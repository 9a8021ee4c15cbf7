// The studio's 3D view, shared by its pages: a GLB from the server drawn
// with three.js on demand (a camera move, a new model), fitted to the
// model on its first load, with the front/side/top/iso views.
import * as THREE from "three";
import { GLTFLoader } from "three/examples/jsm/loaders/GLTFLoader.js";
import { OrbitControls } from "three/examples/jsm/controls/OrbitControls.js";

export class Viewer {
  constructor(el) {
    this.el = el;
    this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(window.devicePixelRatio);
    el.appendChild(this.renderer.domElement);
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0xe9eef2);
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x8a7f70, 1.6));
    const sun = new THREE.DirectionalLight(0xffffff, 1.8);
    sun.position.set(3, 6, 4);
    this.scene.add(sun);
    this.camera = new THREE.PerspectiveCamera(40, 1, 0.01, 10000);
    this.camera.position.set(8, 6, 12);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.addEventListener("change", () => this.render());
    this.model = null;
    // The next load fits the camera to the model; later loads keep it.
    this.fitted = false;
    this.bounds = new THREE.Box3(new THREE.Vector3(-1, 0, -1), new THREE.Vector3(1, 2, 1));
    this.loader = new GLTFLoader();
    this.queued = false;
    window.addEventListener("resize", () => { this.resize(); this.render(); });
  }

  resize() {
    const w = this.el.clientWidth || 400, h = this.el.clientHeight || 300;
    this.renderer.setSize(w, h);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
  }

  // Drawn on demand, not every frame: a big Pailou is hundreds of
  // thousands of triangles, and a browser without a GPU would spend all
  // its time redrawing an unchanged picture.
  render() {
    if (this.queued) return;
    this.queued = true;
    requestAnimationFrame(() => { this.queued = false; this.renderer.render(this.scene, this.camera); });
  }

  view(name) {
    const c = this.bounds.getCenter(new THREE.Vector3());
    const r = this.bounds.getSize(new THREE.Vector3()).length() * 0.5 || 1;
    const d = r / Math.sin((this.camera.fov * Math.PI) / 360) * 1.05;
    const dir = { front: [0, 0, 1], side: [1, 0, 0], top: [0, 1, 0.0001], iso: [1, 0.8, 1] }[name];
    const v = new THREE.Vector3(...dir).normalize().multiplyScalar(d);
    this.camera.position.copy(c).add(v);
    this.camera.near = d / 100; this.camera.far = d * 100;
    this.camera.updateProjectionMatrix();
    this.controls.target.copy(c);
    this.controls.update();
    this.render();
  }

  // Loads the GLB at `url`; the meshes under a node named in `marked`
  // are drawn red. Returns the number of meshes, or null when the server
  // has no model.
  async load(url, marked = [], firstView = "iso") {
    const r = await fetch(url);
    if (!r.ok) return null;
    const gltf = await this.loader.parseAsync(await r.arrayBuffer(), "");
    if (this.model) this.scene.remove(this.model);
    this.model = gltf.scene;
    let meshes = 0;
    const warn = new Set(marked);
    this.model.traverse((o) => {
      if (!o.isMesh) return;
      meshes++;
      let p = o, hit = false;
      while (p) { if (warn.has(p.name)) hit = true; p = p.parent; }
      if (hit) {
        o.material = o.material.clone();
        o.material.color = new THREE.Color(0xff2020);
        o.material.emissive = new THREE.Color(0x660000);
      }
    });
    this.scene.add(this.model);
    this.bounds = new THREE.Box3().setFromObject(this.model);
    this.resize();
    // The camera is fitted to the first model with something in it (an
    // empty one, a new session's, has no extent to fit).
    if (!this.fitted && !this.bounds.isEmpty()) { this.view(firstView); this.fitted = true; }
    this.render();
    return meshes;
  }
}
