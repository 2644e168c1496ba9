// gl_programs.js — the WebGL2 programs from js/generated.js (the desktop GLSL sources assembled as
// GLSL ES 3.00 by nut-viewer --export-web), compiled with errors that name the shader file and line.

// Rewrites "ERROR: 0:123:" (ANGLE's and most browsers' form) as "hni_raycast.frag:17:".
function annotate(log, fileAtLine) {
  return log.replace(/(ERROR|WARNING): \d+:(\d+):/g, (match, kind, lineText) => {
    const line = Number(lineText);
    let file = null;
    for (const [first, name] of fileAtLine) if (first <= line) file = [first, name];
    return file ? `${kind}: ${file[1]}:${line - file[0] + 1}:` : match;
  });
}

// Compiles and links one program of generated.js ({ role, vertex, fragment }); throws one error
// naming the program, the stage and the file lines.
export function buildProgram(gl, program) {
  const id = gl.createProgram();
  for (const [stage, type] of [['vertex', gl.VERTEX_SHADER], ['fragment', gl.FRAGMENT_SHADER]]) {
    const shader = gl.createShader(type);
    gl.shaderSource(shader, program[stage].source);
    gl.compileShader(shader);
    if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS))
      throw new Error(`${program.role}: ${stage} shader, GLSL ES 3.00:\n${annotate(gl.getShaderInfoLog(shader) ?? '', program[stage].fileAtLine)}`);
    gl.attachShader(id, shader);
    gl.deleteShader(shader);
  }
  gl.linkProgram(id);
  if (!gl.getProgramParameter(id, gl.LINK_STATUS)) throw new Error(`${program.role}: link: ${gl.getProgramInfoLog(id)}`);
  const uniforms = new Map();
  return {
    id,
    // The location of a uniform, null when the program does not use it (gl.uniform* ignores null).
    uniform(name) {
      if (!uniforms.has(name)) uniforms.set(name, gl.getUniformLocation(id, name));
      return uniforms.get(name);
    },
  };
}
