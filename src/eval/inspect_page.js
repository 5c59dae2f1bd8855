// The inspection page's script (src/eval/inspect_page.html embeds it; vt inspect writes both
// into one self-contained page). It draws everything from the run's JSON with textContent.
'use strict';
// run: {title, settings: [[name, value]], frames: [{frame, statistics: [[name, value]],
//   images: [{name, width, height, src}], queues: [{label, terms: [name], queue: [[page, level, x,
//   y, priority, streamed, ...term values]], streamed: [page]}]}]}
const run = JSON.parse(document.getElementById('inspect-data').textContent);
const frames = run.frames;
const byId = (id) => document.getElementById(id);
const slider = byId('slider');
let current = -1;

function element(tag, text, className) {
  const e = document.createElement(tag);
  if (text !== undefined) e.textContent = text;
  if (className) e.className = className;
  return e;
}

function formatNumber(v) {
  if (typeof v !== 'number') return v === null || v === undefined ? '\u2013' : String(v);
  if (Number.isInteger(v)) return String(v);
  const a = Math.abs(v);
  if (a >= 1e6 || a < 1e-3) return v.toExponential(3);
  return String(parseFloat(v.toFixed(a >= 100 ? 2 : 4)));
}

function numberCell(v) {
  const td = element('td', formatNumber(v));
  if (typeof v === 'number' && !Number.isInteger(v)) td.title = String(v);
  return td;
}

function showHeader() {
  document.title = run.title || 'vt inspect';
  byId('title').textContent = run.title;
  const settings = byId('settings');
  for (const [name, value] of run.settings) {
    const item = element('span');
    item.append(element('b', name + ' '), value);
    settings.append(item);
  }
  slider.max = String(frames.length - 1);
  document.body.dataset.frames = String(frames.length);
}

// The figures are kept from frame to frame and only their sources change, so the grid does not
// jump while the new images decode.
function showImages(frame) {
  const grid = byId('images');
  while (grid.children.length > frame.images.length) grid.lastChild.remove();
  while (grid.children.length < frame.images.length) {
    const figure = element('figure');
    const img = element('img');
    img.addEventListener('click', () => figure.classList.toggle('wide'));
    figure.append(img, element('figcaption'));
    grid.append(figure);
  }
  frame.images.forEach((image, i) => {
    const figure = grid.children[i];
    const img = figure.querySelector('img');
    img.width = image.width;
    img.height = image.height;
    img.alt = image.name;
    if (img.getAttribute('src') !== image.src) img.src = image.src;
    const caption = figure.querySelector('figcaption');
    caption.replaceChildren(image.name + ' ', element('span', `${image.width}\u00d7${image.height}`));
  });
}

function showStatistics(frame) {
  const body = byId('statistics').tBodies[0];
  body.replaceChildren(...frame.statistics.map(([name, value]) => {
    const tr = element('tr');
    tr.append(element('td', name, 'left'), element('td', value));
    return tr;
  }));
}

// One section per queue (two when configurations are compared), kept from frame to frame.
function queueSection() {
  const table = element('table', undefined, 'queue');
  table.append(element('thead'), element('tbody'));
  const scroll = element('div', undefined, 'queue-box');
  scroll.append(table);
  const section = element('section');
  section.append(element('h2', undefined, 'streamed-heading'), element('div', undefined, 'streamed'),
                 element('h2', undefined, 'queue-heading'), scroll);
  return section;
}

function showQueue(section, queue) {
  const of = queue.label ? ` of ${queue.label}` : '';
  section.querySelector('.streamed-heading').textContent =
      `Streamed for the next frame${of} (${queue.streamed.length})`;
  section.querySelector('.streamed').replaceChildren(
      ...queue.streamed.map((page) => element('span', String(page))));
  const table = section.querySelector('table');
  const head = element('tr');
  for (const name of ['#', 'page', 'level', 'x', 'y', 'priority', ...queue.terms, 'streamed'])
    head.append(element('th', name));
  table.tHead.replaceChildren(head);
  const rows = queue.queue.map(([page, level, x, y, priority, streamed, ...terms], rank) => {
    const tr = element('tr', undefined, streamed ? 'streamed' : '');
    tr.append(numberCell(rank + 1), numberCell(page), numberCell(level), numberCell(x),
              numberCell(y), numberCell(priority), ...terms.map(numberCell),
              element('td', streamed ? '\u2713' : ''));
    return tr;
  });
  table.tBodies[0].replaceChildren(...rows);
  section.querySelector('.queue-heading').textContent =
      `Priority queue${of} (${queue.queue.length})`;
}

function showQueues(frame) {
  const box = byId('queues');
  while (box.children.length > frame.queues.length) box.lastChild.remove();
  while (box.children.length < frame.queues.length) box.append(queueSection());
  frame.queues.forEach((queue, i) => showQueue(box.children[i], queue));
}

function showFrame(index) {
  index = Math.max(0, Math.min(frames.length - 1, index));
  if (index === current) return;
  current = index;
  const frame = frames[index];
  document.body.dataset.frame = String(index);
  slider.value = String(index);
  byId('counter').textContent = `${index + 1} / ${frames.length} \u00b7 frame ${frame.frame}`;
  showImages(frame);
  showStatistics(frame);
  showQueues(frame);
}

const steps = new Map([['ArrowRight', 1], ['n', 1], ['ArrowLeft', -1], ['p', -1],
                       ['PageDown', 10], ['PageUp', -10]]);
document.addEventListener('keydown', (event) => {
  if (event.altKey || event.ctrlKey || event.metaKey) return;
  let target;
  if (steps.has(event.key)) target = current + steps.get(event.key);
  else if (event.key === 'Home') target = 0;
  else if (event.key === 'End') target = frames.length - 1;
  else return;
  event.preventDefault();  // also keeps a focused slider from stepping a second time
  showFrame(target);
});
slider.addEventListener('input', () => showFrame(Number(slider.value)));
byId('previous').addEventListener('click', () => showFrame(current - 1));
byId('next').addEventListener('click', () => showFrame(current + 1));

// The self test drives the page as a user would, through keydown events, and checks what shows.
function press(key) {
  document.body.dispatchEvent(new KeyboardEvent('keydown', {key, bubbles: true, cancelable: true}));
}

function expectFrame(index, after) {
  const shown = document.body.dataset.frame;
  if (shown !== String(index)) throw new Error(`after ${after}: data-frame=${shown}, expected ${index}`);
}

// Waits for the image's load event rather than img.decode(): headless Chromium's virtual time
// waits for loads, not for off-thread decodes, and would end the run before they finish.
function loaded(img) {
  if (img.complete) return Promise.resolve();
  return new Promise((resolve, reject) => {
    img.addEventListener('load', resolve, {once: true});
    img.addEventListener('error', () => reject(new Error(`image ${img.alt} does not load`)), {once: true});
  });
}

async function checkFrame(index) {
  const frame = frames[index];
  const images = Array.from(document.querySelectorAll('#images img'));
  if (images.length !== frame.images.length)
    throw new Error(`frame ${index}: ${images.length} images shown, expected ${frame.images.length}`);
  for (const [i, img] of images.entries()) {
    const image = frame.images[i];
    if (img.src !== image.src) throw new Error(`frame ${index}: image ${image.name} has another source`);
    await loaded(img);
    if (!img.complete || img.naturalWidth !== image.width || img.naturalHeight !== image.height)
      throw new Error(`frame ${index}: image ${image.name} is ${img.naturalWidth}x${img.naturalHeight}`);
  }
  const sections = document.querySelectorAll('#queues > section');
  if (sections.length !== frame.queues.length)
    throw new Error(`frame ${index}: ${sections.length} queues shown, expected ${frame.queues.length}`);
  frame.queues.forEach((queue, i) => {
    const rows = sections[i].querySelectorAll('tbody tr').length;
    if (rows !== queue.queue.length)
      throw new Error(`frame ${index}: ${rows} rows in queue ${i}, expected ${queue.queue.length}`);
    const streamed = sections[i].querySelectorAll('.streamed span').length;
    if (streamed !== queue.streamed.length)
      throw new Error(`frame ${index}: ${streamed} pages streamed in queue ${i}, expected ${queue.streamed.length}`);
  });
}

window.vtSelfTest = async function () {
  const out = byId('selftest');
  out.textContent = 'selftest running';
  const last = frames.length - 1;
  try {
    press('Home');
    expectFrame(0, 'Home');
    await checkFrame(0);
    for (let i = 1; i <= last; ++i) {
      press('ArrowRight');
      expectFrame(i, 'ArrowRight');
      await checkFrame(i);
    }
    const keys = [['ArrowRight', last], ['Home', 0], ['PageDown', Math.min(10, last)],
                  ['End', last], ['p', Math.max(0, last - 1)], ['n', last],
                  ['PageUp', Math.max(0, last - 10)], ['ArrowLeft', Math.max(0, last - 11)]];
    for (const [key, index] of keys) {
      press(key);
      expectFrame(index, key);
    }
    out.textContent = `selftest ok frames=${frames.length}`;
  } catch (error) {
    out.textContent = `selftest failed: ${error.message}`;
  }
  return out.textContent;
};

showHeader();
const start = /^#frame=(\d+)$/.exec(location.hash);
showFrame(start ? Number(start[1]) : 0);
if (location.hash === '#selftest') window.vtSelfTest();
