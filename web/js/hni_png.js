// hni_png.js — an HNI's PNG decoded to its exact RGBA bytes, and the header fields the viewer
// reads before drawing it: the root block's size and its visual summary.
//
// The browser's own image path (img, createImageBitmap, canvas) may premultiply alpha or convert
// colours, and an HNI has many pixels with A = 0 and RGB != 0 whose bytes must survive
// (docs/FORMAT.md, "HNIs in a browser"). So the PNG is decoded here, as nut's reader (libpng)
// decodes it: chunk CRCs checked, the zlib stream inflated by the browser's DecompressionStream,
// scanline filters undone, grey, grey + alpha, RGB and palette widened to RGBA, tRNS to alpha.
// 16-bit and interlaced PNGs are refused, as nut writes neither. Errors are one line.
//
// References: PNG (ISO/IEC 15948), sections 5 (chunks, CRC), 9 (filters), 11 (IHDR, PLTE, tRNS).

const SIGNATURE = [137, 80, 78, 71, 13, 10, 26, 10];

const CRC_TABLE = (() => {
  const table = new Uint32Array(256);
  for (let n = 0; n < 256; ++n) {
    let c = n;
    for (let k = 0; k < 8; ++k) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
    table[n] = c >>> 0;
  }
  return table;
})();

function crc32(bytes, start, end) {
  let c = 0xffffffff;
  for (let i = start; i < end; ++i) c = CRC_TABLE[(c ^ bytes[i]) & 0xff] ^ (c >>> 8);
  return (c ^ 0xffffffff) >>> 0;
}

// Channels per pixel of each colour type.
const CHANNELS = { 0: 1, 2: 3, 3: 1, 4: 2, 6: 4 };

async function inflate(chunks) {
  const stream = new Blob(chunks).stream().pipeThrough(new DecompressionStream('deflate'));
  try {
    return new Uint8Array(await new Response(stream).arrayBuffer());
  } catch (error) {
    throw new Error('corrupt image data (zlib): ' + error.message);
  }
}

// Undoes the scanline filters in place; returns the unfiltered rows without their filter bytes.
function unfilter(data, width, height, bitsPerPixel) {
  const stride = Math.ceil((width * bitsPerPixel) / 8);
  const bpp = Math.max(1, bitsPerPixel >> 3); // the byte distance to the pixel on the left
  if (data.length < height * (stride + 1)) throw new Error('image data too short');
  const out = new Uint8Array(height * stride);
  for (let y = 0; y < height; ++y) {
    const filter = data[y * (stride + 1)];
    const src = y * (stride + 1) + 1;
    const row = y * stride;
    const up = row - stride;
    for (let x = 0; x < stride; ++x) {
      const a = x >= bpp ? out[row + x - bpp] : 0;
      const b = y > 0 ? out[up + x] : 0;
      const c = x >= bpp && y > 0 ? out[up + x - bpp] : 0;
      let predictor;
      switch (filter) {
        case 0: predictor = 0; break;
        case 1: predictor = a; break;
        case 2: predictor = b; break;
        case 3: predictor = (a + b) >> 1; break;
        case 4: {
          const p = a + b - c, pa = Math.abs(p - a), pb = Math.abs(p - b), pc = Math.abs(p - c);
          predictor = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
          break;
        }
        default: throw new Error(`row ${y}: unknown filter type ${filter}`);
      }
      out[row + x] = (data[src + x] + predictor) & 0xff;
    }
  }
  return out;
}

// Decodes a PNG (an ArrayBuffer) to { width, height, pixels: Uint8Array RGBA, row 0 at the top }.
export async function decodePng(buffer) {
  const bytes = new Uint8Array(buffer);
  if (bytes.length < 8 || SIGNATURE.some((v, i) => bytes[i] !== v)) throw new Error('not a PNG file');
  const view = new DataView(buffer);
  let header = null, palette = null, transparency = null, ended = false;
  const idat = [];
  for (let at = 8; !ended; ) {
    if (at + 12 > bytes.length) throw new Error('truncated PNG (no IEND chunk)');
    const length = view.getUint32(at);
    const type = String.fromCharCode(...bytes.subarray(at + 4, at + 8));
    const dataStart = at + 8, dataEnd = dataStart + length;
    if (length > 0x7fffffff || dataEnd + 4 > bytes.length) throw new Error(`truncated PNG (chunk ${type})`);
    if (crc32(bytes, at + 4, dataEnd) !== view.getUint32(dataEnd)) throw new Error(`chunk ${type}: CRC mismatch`);
    const data = bytes.subarray(dataStart, dataEnd);
    if (type === 'IHDR') {
      if (length !== 13) throw new Error('IHDR: wrong length');
      header = {
        width: view.getUint32(dataStart), height: view.getUint32(dataStart + 4),
        depth: data[8], colour: data[9], interlace: data[12],
      };
    } else if (type === 'PLTE') {
      palette = data;
    } else if (type === 'tRNS') {
      transparency = data;
    } else if (type === 'IDAT') {
      idat.push(data);
    } else if (type === 'IEND') {
      ended = true;
    } else if (!(bytes[at + 4] & 0x20)) {
      throw new Error(`unknown critical chunk ${type}`);
    }
    at = dataEnd + 4;
  }
  if (!header) throw new Error('no IHDR chunk');
  const { width, height, depth, colour } = header;
  if (!(colour in CHANNELS)) throw new Error(`unknown colour type ${colour}`);
  if (depth > 8) throw new Error('not an 8-bit PNG (16 bits per channel)');
  if (depth !== 8 && colour !== 0 && colour !== 3) throw new Error(`bit depth ${depth} with colour type ${colour}`);
  if (header.interlace !== 0) throw new Error('interlaced PNG (nut writes none; re-save it without interlacing)');
  if (width === 0 || height === 0) throw new Error('empty image');
  if (colour === 3 && !palette) throw new Error('palette image without PLTE');
  if (idat.length === 0) throw new Error('no IDAT chunk');

  const rows = unfilter(await inflate(idat), width, height, depth * CHANNELS[colour]);
  const stride = Math.ceil((width * depth * CHANNELS[colour]) / 8);
  const pixels = new Uint8Array(width * height * 4);
  // A sample of `depth` bits at index i of a row (depth < 8: packed, most significant first).
  const sample = (row, i) => {
    if (depth === 8) return rows[row + i];
    const bit = i * depth;
    return (rows[row + (bit >> 3)] >> (8 - depth - (bit & 7))) & ((1 << depth) - 1);
  };
  const greyScale = 255 / ((1 << depth) - 1);
  const keyOf = (k) => (transparency && transparency.length >= 2 * (k + 1) ? (transparency[2 * k] << 8) | transparency[2 * k + 1] : -1);
  const greyKey = colour === 0 ? keyOf(0) : -1;
  const rgbKey = colour === 2 ? [keyOf(0), keyOf(1), keyOf(2)] : null;
  for (let y = 0; y < height; ++y) {
    const row = y * stride;
    for (let x = 0; x < width; ++x) {
      const o = 4 * (y * width + x);
      switch (colour) {
        case 6:
          for (let c = 0; c < 4; ++c) pixels[o + c] = rows[row + 4 * x + c];
          break;
        case 2: {
          const r = rows[row + 3 * x], g = rows[row + 3 * x + 1], b = rows[row + 3 * x + 2];
          pixels[o] = r; pixels[o + 1] = g; pixels[o + 2] = b;
          pixels[o + 3] = rgbKey && r === rgbKey[0] && g === rgbKey[1] && b === rgbKey[2] ? 0 : 255;
          break;
        }
        case 4:
          pixels[o] = pixels[o + 1] = pixels[o + 2] = rows[row + 2 * x];
          pixels[o + 3] = rows[row + 2 * x + 1];
          break;
        case 0: {
          const v = sample(row, x);
          pixels[o] = pixels[o + 1] = pixels[o + 2] = Math.round(v * greyScale);
          pixels[o + 3] = v === greyKey ? 0 : 255;
          break;
        }
        case 3: {
          const index = sample(row, x);
          if (3 * index + 2 >= palette.length) throw new Error(`pixel (${x}, ${y}): palette index ${index} out of range`);
          pixels[o] = palette[3 * index]; pixels[o + 1] = palette[3 * index + 1]; pixels[o + 2] = palette[3 * index + 2];
          pixels[o + 3] = transparency && index < transparency.length ? transparency[index] : 255;
          break;
        }
      }
    }
  }
  return { width, height, pixels };
}

// The root block of a decoded HNI: its size in units (mm) and its visual summary, six RGBA colours
// in the order +x, -x, +y, -y, +z, -z (docs/FORMAT.md). Checks what the viewer and the ray caster
// rely on before the image reaches the GPU: the magic, a known version, and the root header with
// the metadata and data items it names inside the image. (The full check is `nut validate`; a
// file that passes these and is still wrong draws wrongly, within the caster's iteration cap.)
export function readHniRoot(image, constants) {
  const { width, height, pixels } = image;
  const texel = (u, v) => {
    if (u < 0 || v < 0 || u >= width || v >= height) throw new Error(`address (${u}, ${v}) outside the ${width}x${height} image`);
    const o = 4 * (v * width + u);
    return pixels.subarray(o, o + 4);
  };
  if (width > constants.maxImageSize || height > constants.maxImageSize)
    throw new Error(`${width}x${height}: larger than an HNI may be (${constants.maxImageSize})`);
  const magic = texel(0, 0);
  if (String.fromCharCode(magic[0], magic[1], magic[2]) !== constants.magic) throw new Error('not an HNI (no NUT magic)');
  if (!constants.versions.includes(magic[3])) throw new Error(`unknown HNI version ${magic[3]}`);
  const root = texel(constants.fileRoot, 0);
  const u = root[0], v = root[1];
  texel(u + constants.headerPixels - 1, v);
  const u24 = (p) => p[0] | (p[1] << 8) | (p[2] << 16);
  const sizeUnits = [0, 1, 2].map((a) => u24(texel(u + constants.headerSize + a, v)));
  if (sizeUnits.some((s) => s === 0)) throw new Error('root block of size 0');
  const cells = [0, 1, 2].map((a) => texel(u + constants.headerSize + a, v)[3] + 1);
  const metaSizes = texel(u + constants.headerMetaSizes, v);
  const xy = texel(u + constants.headerMetaXY, v);
  const z = texel(u + constants.headerMetaZ, v);
  const metaItems = [[xy[0], xy[1]], [xy[2], xy[3]], [z[0], z[1]]];
  metaItems.forEach(([mu, mv], a) => texel(mu + metaSizes[a], mv));
  const data = metaSizes[3] | (z[2] << 8) | (z[3] << 16);
  const du = data & 0xfff, dv = (data >> 12) & 0xfff;
  texel(du + cells[0] * cells[2] - 1, dv + cells[1] - 1);
  const summary = [];
  for (let side = 0; side < 6; ++side) summary.push(Array.from(texel(u + constants.headerSummary + side, v)));
  return { sizeUnits, summary };
}
