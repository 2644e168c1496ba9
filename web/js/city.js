// city.js — the city manifest `city.json` (docs/CITY.md): read and checked by the same rules as
// nut's reader (scene/city.hpp parseCityJson), and where each building stands.

const VERSION = 1;

// A relative path that does not climb out of the manifest's folder.
function staysInside(path) {
  if (typeof path !== 'string' || path === '' || path.startsWith('/') || /^[a-zA-Z][a-zA-Z0-9+.-]*:/.test(path)) return false;
  let depth = 0;
  for (const part of path.split('/')) {
    if (part === '..') --depth;
    else if (part !== '.' && part !== '') ++depth;
    if (depth < 0) return false;
  }
  return depth > 0;
}

const isFinite3 = (v) => Array.isArray(v) && v.length === 3 && v.every((x) => typeof x === 'number' && Number.isFinite(x));

// The world rotation of a building turned by `degrees` about +y (counter-clockwise seen from
// above), as three columns (scene::yawRotation).
export function yawRotation(degrees) {
  const r = (degrees * Math.PI) / 180;
  const c = Math.cos(r), s = Math.sin(r);
  return [[c, 0, -s], [0, 1, 0], [s, 0, c]];
}

// Parses and checks a manifest's text; `where` names it in errors. Returns
// { name, buildings: [{ name, hni, complement, complementLevels: [{ path, errorM }], positionM, yawDeg,
// boundsM }] }.
export function parseCity(text, where) {
  let j;
  try {
    j = JSON.parse(text);
  } catch {
    throw new Error(`${where}: not valid JSON`);
  }
  if (j === null || typeof j !== 'object' || j.format !== 'nut-city') throw new Error(`${where}: not a nut city manifest ("format": "nut-city")`);
  if (j.version !== VERSION) throw new Error(`${where}: unsupported version (this reader knows version ${VERSION})`);
  if (!Array.isArray(j.buildings)) throw new Error(`${where}: "buildings" must be an array`);
  if ('name' in j && typeof j.name !== 'string') throw new Error(`${where}: "name" must be a string`);
  const buildings = j.buildings.map((b, index) => {
    const at = `${where}: building ${index}`;
    if (b === null || typeof b !== 'object' || Array.isArray(b)) throw new Error(`${at}: not an object`);
    if (typeof b.name !== 'string') throw new Error(`${at}: "name" must be a string`);
    const named = `${at} (${b.name})`;
    if (!staysInside(b.hni)) throw new Error(`${named}: "hni" must be a relative path inside the manifest's folder`);
    if ('complement' in b && !staysInside(b.complement))
      throw new Error(`${named}: "complement" must be a relative path inside the manifest's folder`);
    const complementLevels = [];
    if ('complement_levels' in b) {
      const levelsError = `${named}: "complement_levels" must be objects with a "path" inside the manifest's folder ` +
        'and an "error_m" of at least 0, increasing, beside a "complement"';
      if (!Array.isArray(b.complement_levels) || !b.complement) throw new Error(levelsError);
      for (const level of b.complement_levels) {
        if (level === null || typeof level !== 'object' || !staysInside(level.path) || typeof level.error_m !== 'number' ||
            !Number.isFinite(level.error_m) || level.error_m < 0 || level.error_m < (complementLevels.at(-1)?.errorM ?? 0))
          throw new Error(levelsError);
        complementLevels.push({ path: level.path, errorM: level.error_m });
      }
    }
    if (!isFinite3(b.position_m)) throw new Error(`${named}: "position_m" must be three finite numbers`);
    if ('yaw_deg' in b && !(typeof b.yaw_deg === 'number' && Number.isFinite(b.yaw_deg)))
      throw new Error(`${named}: "yaw_deg" must be a finite number`);
    let boundsM = null;
    if ('bounds_m' in b) {
      const box = b.bounds_m;
      if (!Array.isArray(box) || box.length !== 2 || !isFinite3(box[0]) || !isFinite3(box[1]) || box[0].some((v, a) => v > box[1][a]))
        throw new Error(`${named}: "bounds_m" must be two corners of three finite numbers, min <= max`);
      boundsM = { min: box[0], max: box[1] };
    }
    return {
      name: b.name, hni: b.hni, complement: b.complement ?? '', complementLevels, positionM: b.position_m,
      yawDeg: b.yaw_deg ?? 0, boundsM,
    };
  });
  return { name: j.name ?? '', buildings };
}

// The city's box from the manifest: the bounds it gives, else 10 m from each position (as
// nut-viewer fits its camera).
export function manifestBounds(city) {
  const min = [Infinity, Infinity, Infinity], max = [-Infinity, -Infinity, -Infinity];
  for (const b of city.buildings) {
    const box = b.boundsM ?? { min: b.positionM, max: b.positionM.map((v) => v + 10) };
    for (let a = 0; a < 3; ++a) {
      min[a] = Math.min(min[a], box.min[a]);
      max[a] = Math.max(max[a], box.max[a]);
    }
  }
  return { min, max };
}

// The world box of a root block of `sizeM` placed at `originM` with rotation `worldFromRoot`.
export function placedBox(originM, worldFromRoot, sizeM) {
  const min = [Infinity, Infinity, Infinity], max = [-Infinity, -Infinity, -Infinity];
  for (let c = 0; c < 8; ++c) {
    const local = [c & 1 ? sizeM[0] : 0, c & 2 ? sizeM[1] : 0, c & 4 ? sizeM[2] : 0];
    for (let a = 0; a < 3; ++a) {
      const v = originM[a] + worldFromRoot[0][a] * local[0] + worldFromRoot[1][a] * local[1] + worldFromRoot[2][a] * local[2];
      min[a] = Math.min(min[a], v);
      max[a] = Math.max(max[a], v);
    }
  }
  return { min, max };
}
