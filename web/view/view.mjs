// simlab view's page: the model the server names (/view.json, its folder under /model/),
// or model files the user picks or drops, shown in a lab whose panels are generated from
// the model (web/lab/lab.mjs, mountModelViewer). A served model is reloaded when its file
// changes on disk.
import { mountModelViewer, urlSource } from '/lab/lab.mjs';
import { filesOfDrop, pickMainModel } from '/view/files.mjs';

const kReloadPollMs = 1500;

const viewer = document.getElementById('viewer');
let current = null;    // the mounted lab
let watching = null;   // the served model's text, while it is watched for changes

// Mounts the viewer of `source` in place of the one shown.
async function show(source) {
  current?.dispose();
  current = null;
  document.getElementById('title').textContent = source.filename;
  document.title = `${source.filename} · simlab view`;
  current = await mountModelViewer(viewer, source);
  window.lab = current;
  return current;
}

// The served model: shown, then watched for changes of its main file.
async function showServed() {
  const about = await (await fetch('/view.json')).json();
  const source = urlSource(new URL('/model/', document.baseURI), about.file);
  watching = await source.readText(source.filename).catch(() => null);
  await show(source).catch(() => {});
  setInterval(async () => {
    if (watching === null) return;
    const text = await source.readText(source.filename).catch(() => null);
    if (text === null || text === watching) return;
    watching = text;
    await show(source).catch(() => {});
  }, kReloadPollMs);
}

// Files the user gave (File objects): the main model among them, its folder's files read
// from the others by relative path.
async function showLocal(fileList) {
  const files = [...fileList];
  const picked = await pickMainModel(files);
  if (!picked) {
    viewer.textContent = 'No MJCF model (.xml) among the files given.';
    return;
  }
  watching = null;  // (a picked file cannot be watched)
  await show(picked).catch(() => {});
}

for (const id of ['files', 'folder']) {
  document.getElementById(id).addEventListener('change', (event) => showLocal(event.target.files));
}
document.addEventListener('dragover', (event) => {
  event.preventDefault();
  document.body.classList.add('dropping');
});
document.addEventListener('dragleave', () => document.body.classList.remove('dropping'));
document.addEventListener('drop', async (event) => {
  event.preventDefault();
  document.body.classList.remove('dropping');
  showLocal(await filesOfDrop(event.dataTransfer));
});

showServed();
