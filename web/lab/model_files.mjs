// The files an MJCF model pulls in, found the way the loader resolves them, so that the
// lab can fetch them all before compiling (the engine reads from an in-memory folder):
//
//   <include file>             XML, pasted in: relative to the model's folder (else to the
//                              including file's folder)
//   <model file>               XML, a model of its own: relative to the including model's
//                              folder; its assets use its own folder and <compiler>
//   <mesh|hfield|skin|flexcomp file>  bytes, in <compiler meshdir> (else assetdir)
//   <texture file, fileright, fileleft, fileup, filedown, filefront, fileback>
//                              bytes, in <compiler texturedir> (else assetdir)
//
// <compiler strippath="true"> drops the folders of asset names. Absolute names and names
// that climb out of the main model's folder are left to the engine (it reports them).
// No DOM is needed: the module runs in node as well (web/test/model_files.mjs).

const kTextureAttributes = ['file', 'fileright', 'fileleft', 'fileup', 'filedown', 'filefront', 'fileback'];

// The start tags of an XML text, comments and CDATA skipped: [{tag, attrs: {name: value}}].
export function startTags(xml) {
  const text = xml.replace(/<!--[\s\S]*?-->/g, '').replace(/<!\[CDATA\[[\s\S]*?\]\]>/g, '');
  const tags = [];
  const tagPattern = /<([A-Za-z_][\w.:-]*)((?:\s+[^\s=/>]+\s*=\s*(?:"[^"]*"|'[^']*'))*)\s*\/?>/g;
  const attrPattern = /([^\s=/>]+)\s*=\s*(?:"([^"]*)"|'([^']*)')/g;
  for (const [, tag, attrText] of text.matchAll(tagPattern)) {
    const attrs = {};
    for (const [, name, double, single] of attrText.matchAll(attrPattern)) attrs[name] = decodeEntities(double ?? single);
    tags.push({ tag, attrs });
  }
  return tags;
}

function decodeEntities(value) {
  return value.replace(/&(lt|gt|quot|apos|amp);/g, (_, name) => ({ lt: '<', gt: '>', quot: '"', apos: "'", amp: '&' })[name]);
}

// "a/./b/../c" -> "a/c"; null for absolute names or names that climb above the root.
export function normalizePath(path) {
  if (path.startsWith('/') || /^[A-Za-z]:[\\/]/.test(path)) return null;
  const parts = [];
  for (const part of path.split(/[\\/]+/)) {
    if (part === '' || part === '.') continue;
    if (part === '..') {
      if (!parts.length) return null;
      parts.pop();
    } else {
      parts.push(part);
    }
  }
  return parts.join('/');
}

function folderOf(path) {
  const slash = path.lastIndexOf('/');
  return slash < 0 ? '' : path.slice(0, slash + 1);
}

// A folder attribute as a prefix ("meshes" -> "meshes/").
function asFolder(dir) {
  return dir && !dir.endsWith('/') ? `${dir}/` : dir ?? '';
}

// The <compiler> settings that place assets (the last one wins per attribute).
function assetFolders(tags) {
  const c = {};
  for (const { tag, attrs } of tags) if (tag === 'compiler') Object.assign(c, attrs);
  return {
    mesh: asFolder(c.meshdir || c.assetdir),
    texture: asFolder(c.texturedir || c.assetdir),
    strip: c.strippath === 'true',
  };
}

// The asset files of a model's tags: [{path, kind}] relative to the root.
function assetPaths(tags, modelFolder) {
  const folders = assetFolders(tags);
  const found = [];
  const add = (name, folder) => {
    const file = folders.strip ? name.slice(name.lastIndexOf('/') + 1) : name;
    found.push(modelFolder + folder + file);
  };
  for (const { tag, attrs } of tags) {
    const meshlike = tag === 'mesh' || tag === 'hfield' || tag === 'skin' || tag === 'flexcomp';
    if (meshlike && attrs.file) add(attrs.file, folders.mesh);
    if (tag === 'texture') {
      for (const name of kTextureAttributes) if (attrs[name]) add(attrs[name], folders.texture);
    }
  }
  return found;
}

// Every file the model `mainName` needs besides itself: {path relative to its folder:
// text (XML) or Uint8Array}. readText(path) / readBytes(path) fetch one file relative to
// the model's folder and reject when it is missing.
export async function gatherModelFiles(mainName, mainXml, readText, readBytes) {
  const files = {};
  const binaries = new Set();
  const texts = new Map([[mainName, mainXml]]);
  const readXml = async (path) => {
    if (!texts.has(path)) texts.set(path, await readText(path));
    return texts.get(path);
  };

  // One model document: its includes pasted in (recursively), its attached models, its assets.
  const visitModel = async (path) => {
    const modelFolder = folderOf(path);
    const tags = await withIncludes(path, modelFolder, readXml, files);
    for (const { tag, attrs } of tags) {
      if (tag !== 'model' || !attrs.file) continue;
      const child = normalizePath(modelFolder + attrs.file);
      if (child === null || child in files || child === mainName) continue;
      files[child] = await readXml(child);
      await visitModel(child);
    }
    for (const asset of assetPaths(tags, modelFolder)) {
      const clean = normalizePath(asset);
      if (clean !== null && !(clean in files)) binaries.add(clean);
    }
  };
  await visitModel(mainName);

  // Meshes, textures and height fields, fetched together.
  const paths = [...binaries].filter((p) => !(p in files));
  const bytes = await Promise.all(paths.map((p) => readBytes(p)));
  paths.forEach((p, i) => { files[p] = bytes[i]; });
  return files;
}

// The start tags of `path` with the files it includes pasted in place, in document order.
// An include names a file in the model's folder, else beside the including file.
async function withIncludes(path, modelFolder, readXml, files, depth = 0) {
  if (depth > 32) throw new Error(`${path}: includes are nested too deeply`);
  const tags = [];
  for (const entry of startTags(await readXml(path))) {
    if (entry.tag !== 'include' || !entry.attrs.file) {
      tags.push(entry);
      continue;
    }
    const included = await includedPath(entry.attrs.file, modelFolder, folderOf(path), readXml, files);
    if (included !== null) tags.push(...await withIncludes(included, modelFolder, readXml, files, depth + 1));
  }
  return tags;
}

// Reads an included file into `files`; returns its path (null if it cannot be named).
async function includedPath(name, modelFolder, includerFolder, readXml, files) {
  const first = normalizePath(modelFolder + name);
  const second = normalizePath(includerFolder + name);
  if (first === null && second === null) return null;
  for (const candidate of [first, second]) {
    if (candidate !== null && candidate in files) return candidate;
  }
  try {
    if (first === null) throw new Error(`${name}: outside the model's folder`);
    files[first] = await readXml(first);
    return first;
  } catch (error) {
    if (second === null || second === first) throw error;
    files[second] = await readXml(second);
    return second;
  }
}
