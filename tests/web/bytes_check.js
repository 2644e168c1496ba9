// The byte test's page (bytes_check.html): writes window.bytesCheck = { files: [{ name, width,
// height, decoded, uploaded, error }] }, where decoded and uploaded count the bytes that differ
// from NAME.rgba after decoding and after the round trip through the RGBA8UI atlas texture.
import { AtlasPages } from './js/atlas.js';
import { decodePng } from './js/hni_png.js';

function differences(a, b) {
  if (a.length !== b.length) return Math.max(a.length, b.length);
  let n = 0;
  for (let i = 0; i < a.length; ++i) n += a[i] !== b[i] ? 1 : 0;
  return n;
}

// Reads a rectangle of an RGBA8UI texture back as bytes.
function readBack(gl, texture, [u, v], width, height) {
  const framebuffer = gl.createFramebuffer();
  gl.bindFramebuffer(gl.FRAMEBUFFER, framebuffer);
  gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, texture, 0);
  const words = new Uint32Array(width * height * 4);
  gl.readPixels(u, v, width, height, gl.RGBA_INTEGER, gl.UNSIGNED_INT, words);
  gl.bindFramebuffer(gl.FRAMEBUFFER, null);
  gl.deleteFramebuffer(framebuffer);
  if (gl.getError() !== gl.NO_ERROR) throw new Error('readPixels failed');
  return Uint8Array.from(words);
}

async function run() {
  const gl = document.createElement('canvas').getContext('webgl2');
  if (!gl) throw new Error('no WebGL2');
  const names = await (await fetch('files.json')).json();
  const pages = new AtlasPages(gl, 4096, 1);
  const files = [];
  for (const name of names) {
    const entry = { name };
    try {
      const [png, raw] = await Promise.all(
        [name, `${name}.rgba`].map(async (path) => new Uint8Array(await (await fetch(path)).arrayBuffer())));
      const image = await decodePng(png.buffer);
      Object.assign(entry, { width: image.width, height: image.height, decoded: differences(image.pixels, raw) });
      if (pages.pages.length) pages.clear(0);
      const slot = pages.place(image);
      entry.uploaded = differences(readBack(gl, pages.texture(slot.page), slot.origin, image.width, image.height), raw);
    } catch (error) {
      entry.error = error.message;
    }
    files.push(entry);
  }
  return { files };
}

run()
  .then((result) => {
    window.bytesCheck = result;
    document.getElementById('result').textContent = JSON.stringify(result, null, 1);
    document.body.dataset.state = 'done';
  })
  .catch((error) => {
    window.bytesCheck = { error: error.message };
    document.body.dataset.state = 'done';
  });
