// The parts of three.js that src/report/assets/report3d.js uses, bundled into one classic
// script that defines the global THREE (see README.md in this folder).
export {
  ArrowHelper, AxesHelper, Box3, BoxGeometry, BufferGeometry, Color, CylinderGeometry,
  DirectionalLight, Group, HemisphereLight, Line, LineBasicMaterial, Mesh, MeshLambertMaterial,
  PerspectiveCamera, Quaternion, Scene, SphereGeometry, TorusGeometry, Vector3, WebGLRenderer,
} from 'three';
export { OrbitControls } from 'three/addons/controls/OrbitControls.js';
