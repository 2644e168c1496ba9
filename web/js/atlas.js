// atlas.js — HNIs streamed into atlas pages, as the desktop viewer does (viewer/atlas_pages.hpp):
// square RGBA8UI textures read with texelFetch, so the bytes reach the shader exactly (no
// filtering, no normalisation, no premultiplication). An HNI goes to the first page with room; a
// new page opens when none has, up to the limit that bounds the texture memory. Within a page the
// HNIs are laid out in shelves (rows as tall as their tallest HNI), which is simple and wastes
// little on a city's HNIs of similar heights; every address inside an HNI is relative to its
// origin, so any layout works.

// Rows of HNIs, each shelf as tall as the first HNI placed on it.
class ShelfBin {
  constructor(size) {
    this.size = size;
    this.shelves = []; // { y, height, x }
    this.top = 0;
  }

  // The origin [u, v] for a width x height rectangle, or null when the page has no room.
  insert(width, height) {
    if (width > this.size || height > this.size) return null;
    // The lowest shelf tall enough with room left, preferring the tightest height.
    let best = null;
    for (const shelf of this.shelves)
      if (shelf.height >= height && this.size - shelf.x >= width && (!best || shelf.height < best.height)) best = shelf;
    if (!best) {
      if (this.top + height > this.size) return null;
      best = { y: this.top, height, x: 0 };
      this.shelves.push(best);
      this.top += height;
    }
    const origin = [best.x, best.y];
    best.x += width;
    return origin;
  }

  fits(width, height) {
    if (width > this.size || height > this.size) return false;
    return this.shelves.some((s) => s.height >= height && this.size - s.x >= width) || this.top + height <= this.size;
  }
}

export class AtlasPages {
  // Pages of pageSize^2 texels (at most MAX_TEXTURE_SIZE), at most maxPages of them.
  constructor(gl, pageSize, maxPages) {
    this.gl = gl;
    this.pageSize = Math.min(pageSize, gl.getParameter(gl.MAX_TEXTURE_SIZE));
    this.maxPages = maxPages;
    this.pages = []; // { texture, bin }
  }

  // Whether place() would find room: in an open page, or by opening one.
  fits(image) {
    if (image.width > this.pageSize || image.height > this.pageSize) return false;
    return this.pages.length < this.maxPages || this.pages.some((p) => p.bin.fits(image.width, image.height));
  }

  // Uploads a decoded HNI ({ width, height, pixels }) into a page: { page, origin: [u, v] }.
  place(image) {
    const { width, height } = image;
    if (width > this.pageSize || height > this.pageSize)
      throw new Error(`a ${width}x${height} HNI exceeds the ${this.pageSize}^2 atlas page`);
    for (let p = 0; p < this.pages.length; ++p) {
      const origin = this.pages[p].bin.insert(width, height);
      if (origin) return this.put(p, origin, image);
    }
    if (this.pages.length >= this.maxPages) throw new Error(`the atlas is full: ${this.maxPages} pages of ${this.pageSize}^2`);
    this.pages.push({ texture: this.createTexture(), bin: new ShelfBin(this.pageSize) });
    return this.put(this.pages.length - 1, this.pages.at(-1).bin.insert(width, height), image);
  }

  // Empties a page for reuse: what it held must no longer be drawn.
  clear(page) {
    this.pages[page].bin = new ShelfBin(this.pageSize);
  }

  texture(page) {
    return this.pages[page].texture;
  }

  // Texture memory of the open pages (4 bytes a texel).
  bytes() {
    return this.pages.length * this.pageSize * this.pageSize * 4;
  }

  createTexture() {
    const gl = this.gl;
    const texture = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, texture);
    // Integer textures must not be filtered (or the texture is incomplete); texelFetch never does.
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
    gl.texStorage2D(gl.TEXTURE_2D, 1, gl.RGBA8UI, this.pageSize, this.pageSize);
    gl.bindTexture(gl.TEXTURE_2D, null);
    const error = gl.getError();
    if (error !== gl.NO_ERROR) throw new Error(`atlas page ${this.pageSize}^2: GL error 0x${error.toString(16)}`);
    return texture;
  }

  put(page, origin, image) {
    const gl = this.gl;
    gl.bindTexture(gl.TEXTURE_2D, this.pages[page].texture);
    // From typed arrays these have no effect, but say what the bytes must not go through.
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
    gl.pixelStorei(gl.UNPACK_FLIP_Y_WEBGL, false);
    gl.pixelStorei(gl.UNPACK_PREMULTIPLY_ALPHA_WEBGL, false);
    gl.pixelStorei(gl.UNPACK_COLORSPACE_CONVERSION_WEBGL, gl.NONE);
    gl.texSubImage2D(gl.TEXTURE_2D, 0, origin[0], origin[1], image.width, image.height, gl.RGBA_INTEGER, gl.UNSIGNED_BYTE, image.pixels);
    gl.bindTexture(gl.TEXTURE_2D, null);
    return { page, origin };
  }
}
