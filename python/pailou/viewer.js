// pailou's notebook viewer: a scene's arrays (base64 of float32 positions,
// normals, colours and uint32 triangle indices) drawn with WebGL, turned
// by dragging and zoomed with the wheel. No other file or network access:
// the package compiles this file into Scene._repr_html_.
window.pailouView = window.pailouView || function (canvas, data) {
  function decode(b64, Type) {
    var s = atob(b64), bytes = new Uint8Array(s.length);
    for (var i = 0; i < s.length; i++) bytes[i] = s.charCodeAt(i);
    return new Type(bytes.buffer);
  }
  var pos = decode(data.positions, Float32Array);
  var nor = decode(data.normals, Float32Array);
  var col = decode(data.colors, Float32Array);
  var idx = decode(data.indices, Uint32Array);
  var gl = canvas.getContext("webgl2") || canvas.getContext("webgl");
  if (!gl || (!(gl instanceof WebGL2RenderingContext) && !gl.getExtension("OES_element_index_uint"))) {
    canvas.replaceWith(document.createTextNode("pailou: this browser has no WebGL; use scene.write('model.glb')"));
    return;
  }
  // The model's box: the view looks at its centre from a distance that fits it.
  var lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (var i = 0; i < pos.length; i += 3) for (var k = 0; k < 3; k++) {
    lo[k] = Math.min(lo[k], pos[i + k]); hi[k] = Math.max(hi[k], pos[i + k]);
  }
  if (pos.length === 0) { lo = [-1, -1, -1]; hi = [1, 1, 1]; }
  var centre = [0, 1, 2].map(function (k) { return (lo[k] + hi[k]) / 2; });
  var radius = Math.max(1e-6, Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) / 2);
  var vs = "attribute vec3 p; attribute vec3 n; attribute vec3 c; uniform mat4 m; varying vec3 vn; varying vec3 vc;" +
    "void main(){ gl_Position = m * vec4(p, 1.0); vn = n; vc = c; }";
  var fs = "precision mediump float; varying vec3 vn; varying vec3 vc; uniform vec3 l;" +
    "void main(){ float d = abs(dot(normalize(vn), l)); gl_FragColor = vec4(vc * (0.35 + 0.65 * d), 1.0); }";
  function shader(type, src) {
    var s = gl.createShader(type); gl.shaderSource(s, src); gl.compileShader(s); return s;
  }
  var prog = gl.createProgram();
  gl.attachShader(prog, shader(gl.VERTEX_SHADER, vs));
  gl.attachShader(prog, shader(gl.FRAGMENT_SHADER, fs));
  gl.linkProgram(prog); gl.useProgram(prog);
  function attribute(name, array) {
    var b = gl.createBuffer(); gl.bindBuffer(gl.ARRAY_BUFFER, b);
    gl.bufferData(gl.ARRAY_BUFFER, array, gl.STATIC_DRAW);
    var loc = gl.getAttribLocation(prog, name);
    gl.enableVertexAttribArray(loc); gl.vertexAttribPointer(loc, 3, gl.FLOAT, false, 0, 0);
  }
  attribute("p", pos); attribute("n", nor); attribute("c", col);
  var ib = gl.createBuffer(); gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, ib);
  gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, idx, gl.STATIC_DRAW);
  var uM = gl.getUniformLocation(prog, "m"), uL = gl.getUniformLocation(prog, "l");
  var yaw = 0.7, pitch = 0.35, dist = 2.6 * radius;
  function draw() {
    var w = canvas.width, h = canvas.height;
    gl.viewport(0, 0, w, h); gl.clearColor(1, 1, 1, 1);
    gl.enable(gl.DEPTH_TEST); gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    // Eye on a sphere around the centre, y up; a perspective of 40 degrees.
    var eye = [centre[0] + dist * Math.cos(pitch) * Math.sin(yaw), centre[1] + dist * Math.sin(pitch),
      centre[2] + dist * Math.cos(pitch) * Math.cos(yaw)];
    var f = norm(sub(centre, eye)), s = norm(cross(f, [0, 1, 0])), u = cross(s, f);
    var view = [s[0], u[0], -f[0], 0, s[1], u[1], -f[1], 0, s[2], u[2], -f[2], 0,
      -dot(s, eye), -dot(u, eye), dot(f, eye), 1];
    var near = Math.max(dist - 2 * radius, dist / 1000), far = dist + 2 * radius, t = 1 / Math.tan(Math.PI / 9);
    var proj = [t * h / w, 0, 0, 0, 0, t, 0, 0, 0, 0, (far + near) / (near - far), -1, 0, 0, 2 * far * near / (near - far), 0];
    gl.uniformMatrix4fv(uM, false, mul(proj, view));
    gl.uniform3fv(uL, norm([0.4, 0.8, 0.5]));
    gl.drawElements(gl.TRIANGLES, idx.length, gl.UNSIGNED_INT, 0);
  }
  function sub(a, b) { return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]; }
  function dot(a, b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
  function cross(a, b) { return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]; }
  function norm(a) { var l = Math.hypot(a[0], a[1], a[2]) || 1; return [a[0] / l, a[1] / l, a[2] / l]; }
  function mul(a, b) { // column-major 4x4 product a * b
    var o = new Float32Array(16);
    for (var c = 0; c < 4; c++) for (var r = 0; r < 4; r++) {
      var v = 0; for (var k = 0; k < 4; k++) v += a[k * 4 + r] * b[c * 4 + k]; o[c * 4 + r] = v;
    }
    return o;
  }
  var dragging = null;
  canvas.addEventListener("mousedown", function (e) { dragging = [e.clientX, e.clientY]; });
  window.addEventListener("mouseup", function () { dragging = null; });
  window.addEventListener("mousemove", function (e) {
    if (!dragging) return;
    yaw -= (e.clientX - dragging[0]) * 0.01;
    pitch = Math.max(-1.5, Math.min(1.5, pitch + (e.clientY - dragging[1]) * 0.01));
    dragging = [e.clientX, e.clientY]; draw();
  });
  canvas.addEventListener("wheel", function (e) {
    e.preventDefault(); dist *= Math.exp(e.deltaY * 0.001); draw();
  }, { passive: false });
  draw();
};
