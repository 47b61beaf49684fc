// The lesson page's entry: fetches the lesson text the server names (/lesson.txt),
// parses it and renders it into <main id="lesson">. The live lab module
// (web/lab/lab.mjs, served at /lab/lab.mjs) is imported only when a lab block needs it,
// so the page works (with a placeholder) while that module is absent.
import { parseLesson } from './parse.mjs';
import { renderLesson } from './render.mjs';

// The title line from the lesson's file name: "lesson-2.3-actuators.txt" -> "Lesson 2.3: actuators".
function titleFromName(name) {
  const m = /lesson-([\d.]+)-(.+?)(\.\w+)?$/.exec(name);
  return m ? `Lesson ${m[1]}: ${m[2].replace(/[-_]/g, ' ')}` : name;
}

async function main() {
  const status = document.getElementById('status');
  const root = document.getElementById('lesson');
  try {
    const response = await fetch('/lesson.txt');
    if (!response.ok) throw new Error(`/lesson.txt: HTTP ${response.status}`);
    const text = await response.text();
    const about = await fetch('/lesson.json').then((r) => r.json()).catch(() => ({}));
    const name = about.file ?? 'lesson';
    document.getElementById('title').textContent = titleFromName(name);
    const lesson = parseLesson(text);
    renderLesson(lesson, root, {
      baseUrl: new URL('/', location.href).href,
      loadLab: () => import('/lab/lab.mjs'),
      fetchText: async (url) => {
        const reply = await fetch(url);
        if (!reply.ok) throw new Error(`${url}: HTTP ${reply.status}`);
        return reply.text();
      },
    });
    document.body.dataset.ready = 'true';
    status.remove();
  } catch (e) {
    status.textContent = `The lesson could not be shown: ${e.message}`;
    status.className = 'error';
    document.body.dataset.ready = 'error';
  }
}

main();
