// The parts of three.js that report.js uses, bundled into one global (THREE) so that report.html
// needs no module import and opens from file://.
export {BufferGeometry, Color, Float32BufferAttribute, Group, Line, LineBasicMaterial, LineSegments, PerspectiveCamera, Points, PointsMaterial, Quaternion, Scene, Vector3, WebGLRenderer} from 'three';
export {OrbitControls} from 'three/examples/jsm/controls/OrbitControls.js';
