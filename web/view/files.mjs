// Model files the user gives the viewer (picked files, a picked folder, or a drop of
// either): each with its path relative to the folder given, the main model among them,
// and a source that reads the others by the paths the model names. No DOM beyond File
// and drag-and-drop entries, so node can test pickMainModel with File-like objects.

// Each item as {file, path}: a File with its webkitRelativePath (a picked folder), its
// name, or an item already carrying a path (a dropped folder); a folder common to every
// path is taken off, so paths are relative to the model's folder.
export function withPaths(items) {
  const entries = items.map((item) => (item.file ? item : { file: item, path: item.webkitRelativePath || item.name }));
  const first = entries[0]?.path.split('/') ?? [];
  const top = first.length > 1 ? `${first[0]}/` : null;
  const shared = top && entries.every((e) => e.path.startsWith(top));
  return entries.map((e) => ({ file: e.file, path: shared ? e.path.slice(top.length) : e.path }));
}

// The basename of a path.
function basename(path) {
  return path.slice(path.lastIndexOf('/') + 1);
}

// A model source (see web/lab/lab.mjs, urlSource) over the given files, whose main
// model is the .xml file no other .xml names in a file= attribute (the shallowest, then
// the first by name, when several are); null when there is no .xml file.
export async function pickMainModel(items) {
  const entries = withPaths(items);
  const models = entries.filter((e) => e.path.toLowerCase().endsWith('.xml'));
  if (!models.length) return null;
  const texts = await Promise.all(models.map((e) => e.file.text()));
  const named = new Set();
  for (const text of texts) {
    for (const match of text.matchAll(/\bfile\s*=\s*["']([^"']+)["']/g)) named.add(basename(match[1]));
  }
  const depth = (path) => path.split('/').length;
  const candidates = models.filter((e) => !named.has(basename(e.path)));
  const main = (candidates.length ? candidates : models)
    .sort((a, b) => depth(a.path) - depth(b.path) || a.path.localeCompare(b.path))[0];
  const byPath = new Map(entries.map((e) => [e.path, e.file]));
  const find = (path) => {
    const file = byPath.get(path.replace(/^\.\//, ''));
    if (!file) throw new Error(`${path}: not among the files given (give the model's whole folder)`);
    return file;
  };
  return {
    filename: main.path,
    readText: async (path) => find(path).text(),
    readBytes: async (path) => new Uint8Array(await find(path).arrayBuffer()),
  };
}

// The files of a drop, folders walked, each with its path from the dropped folder.
export async function filesOfDrop(dataTransfer) {
  const roots = [...dataTransfer.items].map((item) => item.webkitGetAsEntry?.()).filter(Boolean);
  if (!roots.length) return [...dataTransfer.files];
  const out = [];
  const walk = async (entry, prefix) => {
    if (entry.isFile) {
      const file = await new Promise((resolve, reject) => entry.file(resolve, reject));
      out.push({ file, path: prefix + entry.name });
      return;
    }
    const reader = entry.createReader();
    for (;;) {
      const batch = await new Promise((resolve, reject) => reader.readEntries(resolve, reject));
      if (!batch.length) break;
      for (const child of batch) await walk(child, `${prefix}${entry.name}/`);
    }
  };
  for (const root of roots) await walk(root, '');
  return out;
}
