#include "eval/inspect_page.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string_view>

#include "common/error.h"
#include "common/posix_file.h"

namespace vt {
namespace {

// The page around the data. Everything is drawn by the script from the JSON, with textContent, so
// no string of the run is ever parsed as HTML. kDataMarker is replaced by the run's JSON.
constexpr std::string_view kDataMarker = "@INSPECT_DATA@";
constexpr std::string_view kPageTemplate = R"html(<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>vt inspect</title>
<style>
  :root { color-scheme: light dark; font: 14px system-ui, sans-serif; }
  body { margin: 0 16px 24px; }
  h1 { font-size: 1.3em; margin: 12px 0 4px; overflow-wrap: anywhere; }
  h2 { font-size: 1.05em; margin: 16px 0 6px; }
  #settings { display: flex; flex-wrap: wrap; gap: 2px 18px; margin: 0 0 6px; opacity: 0.75; }
  #settings b { font-weight: 600; }
  #controls { position: sticky; top: 0; z-index: 2; display: flex; gap: 8px; align-items: center;
              padding: 8px 0; background: Canvas; border-bottom: 1px solid #8885; }
  #slider { flex: 1; }
  #counter { min-width: 17em; font-variant-numeric: tabular-nums; }
  #keys { opacity: 0.6; font-size: 0.9em; }
  #images { display: grid; grid-template-columns: repeat(auto-fill, minmax(320px, 1fr));
            gap: 12px; margin: 12px 0; }
  figure { margin: 0; }
  figure.wide { grid-column: 1 / -1; }
  figure img { display: block; width: 100%; height: auto; image-rendering: pixelated;
               cursor: zoom-in; border: 1px solid #8885;
               background: repeating-conic-gradient(#8884 0 25%, transparent 0 50%) 0 0 / 16px 16px; }
  figure.wide img { cursor: zoom-out; }
  figcaption { padding: 2px 0; }
  figcaption span { opacity: 0.6; }
  #panels { display: flex; flex-wrap: wrap; gap: 8px 32px; align-items: flex-start; }
  table { border-collapse: collapse; font-variant-numeric: tabular-nums; }
  th, td { padding: 2px 8px; text-align: right; border-bottom: 1px solid #8883; white-space: nowrap; }
  th { background: Canvas; position: sticky; top: 0; }
  .left { text-align: left; }
  #queue-box { max-height: 75vh; overflow: auto; }
  #queue tr.streamed td { background: #2a85; }
  #streamed { max-width: 40em; line-height: 1.7; }
  #streamed span { display: inline-block; padding: 0 5px; margin: 0 3px 0 0; border-radius: 3px;
                   background: #2a85; font-variant-numeric: tabular-nums; }
  #selftest { display: block; margin-top: 16px; opacity: 0.6; }
</style>
</head>
<body>
<header>
  <h1 id="title"></h1>
  <div id="settings"></div>
</header>
<div id="controls">
  <button id="previous" title="previous frame (Left, p)">&#9664;</button>
  <button id="next" title="next frame (Right, n)">&#9654;</button>
  <input id="slider" type="range" min="0" value="0" step="1" aria-label="frame">
  <span id="counter"></span>
  <span id="keys">&larr; &rarr; n p: 1 &middot; PgUp PgDn: 10 &middot; Home End</span>
</div>
<div id="images"></div>
<div id="panels">
  <section>
    <h2>Statistics</h2>
    <table id="statistics"><tbody></tbody></table>
    <h2 id="streamed-heading">Streamed</h2>
    <div id="streamed"></div>
  </section>
  <section>
    <h2 id="queue-heading">Priority queue</h2>
    <div id="queue-box"><table id="queue"><thead></thead><tbody></tbody></table></div>
  </section>
</div>
<output id="selftest"></output>
<script type="application/json" id="inspect-data">@INSPECT_DATA@</script>
<script>
'use strict';
// run: {title, settings: [[name, value]], frames: [{frame, statistics: [[name, value]],
//   images: [{name, width, height, src}], terms: [name], queue: [[page, level, x, y, priority,
//   streamed, ...term values]], streamed: [page]}]}
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

function showQueue(frame) {
  const table = byId('queue');
  const head = element('tr');
  for (const name of ['#', 'page', 'level', 'x', 'y', 'priority', ...frame.terms, 'streamed'])
    head.append(element('th', name));
  table.tHead.replaceChildren(head);
  const rows = frame.queue.map(([page, level, x, y, priority, streamed, ...terms], rank) => {
    const tr = element('tr', undefined, streamed ? 'streamed' : '');
    tr.append(numberCell(rank + 1), numberCell(page), numberCell(level), numberCell(x),
              numberCell(y), numberCell(priority), ...terms.map(numberCell),
              element('td', streamed ? '\u2713' : ''));
    return tr;
  });
  table.tBodies[0].replaceChildren(...rows);
  byId('queue-heading').textContent = `Priority queue (${frame.queue.length})`;
}

function showStreamed(frame) {
  byId('streamed-heading').textContent = `Streamed for the next frame (${frame.streamed.length})`;
  byId('streamed').replaceChildren(...frame.streamed.map((page) => element('span', String(page))));
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
  showQueue(frame);
  showStreamed(frame);
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
  const rows = document.querySelectorAll('#queue tbody tr').length;
  if (rows !== frame.queue.length)
    throw new Error(`frame ${index}: ${rows} queue rows, expected ${frame.queue.length}`);
  const streamed = document.querySelectorAll('#streamed span').length;
  if (streamed !== frame.streamed.length)
    throw new Error(`frame ${index}: ${streamed} streamed pages, expected ${frame.streamed.length}`);
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
</script>
</body>
</html>
)html";

using nlohmann::json;

constexpr char kBase64Alphabet[] =
    "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

// Empty when the image can be encoded, else what is wrong with it.
std::string imageProblem(const InspectImage& image) {
  const std::string name = "image '" + image.name + "'";
  if (image.width <= 0 || image.height <= 0)
    return name + ": size " + std::to_string(image.width) + " x " + std::to_string(image.height) +
           " is not positive";
  const uint64_t expected = uint64_t(image.width) * uint64_t(image.height) * 4;
  if (image.rgba.size() != expected)
    return name + ": " + std::to_string(image.rgba.size()) + " bytes of RGBA, expected " +
           std::to_string(image.width) + " x " + std::to_string(image.height) +
           " x 4 = " + std::to_string(expected);
  return {};
}

json pairsJson(const std::vector<std::pair<std::string, std::string>>& pairs) {
  json array = json::array();
  for (const auto& [name, value] : pairs) array.push_back(json::array({name, value}));
  return array;
}

// Queue rows are arrays [page, level, x, y, priority, streamed, term values...] under the frame's
// term names, the union of the requests' terms in order of first appearance (null where a request
// lacks one): a queue has thousands of rows, and names once per frame keep the page small.
json frameJson(const InspectFrame& frame) {
  json images = json::array();
  for (const InspectImage& image : frame.images)
    images.push_back({{"name", image.name},
                      {"width", image.width},
                      {"height", image.height},
                      {"src", "data:image/png;base64," + encodeBase64(encodePng(image))}});
  std::vector<std::string> terms;
  for (const InspectRequest& request : frame.queue)
    for (const InspectTerm& term : request.terms)
      if (std::find(terms.begin(), terms.end(), term.name) == terms.end())
        terms.push_back(term.name);
  json queue = json::array();
  for (const InspectRequest& request : frame.queue) {
    json row = {request.page, request.level,    request.x,
                request.y,    request.priority, request.streamed};
    std::vector<json> values(terms.size());  // null where the request has no such term
    for (const InspectTerm& term : request.terms)
      values[std::find(terms.begin(), terms.end(), term.name) - terms.begin()] = term.value;
    for (json& value : values) row.push_back(std::move(value));
    queue.push_back(std::move(row));
  }
  return {{"frame", frame.frame},        {"statistics", pairsJson(frame.statistics)},
          {"images", std::move(images)}, {"terms", terms},
          {"queue", std::move(queue)},   {"streamed", frame.streamed}};
}

// '<' only occurs inside JSON strings, where \u003c means the same; without it no "</script" or
// "<!--" can reach the HTML parser. (UTF-8 never has the byte 0x3C inside a multi-byte character.)
void appendScriptSafe(std::string& out, std::string_view jsonText) {
  for (const char c : jsonText) {
    if (c == '<')
      out += "\\u003c";
    else
      out += c;
  }
}

}  // namespace

std::string encodeBase64(std::span<const uint8_t> bytes) {
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  size_t i = 0;
  // Each 3 bytes become 4 characters of 6 bits, most significant first (RFC 4648 section 4).
  for (; i + 3 <= bytes.size(); i += 3) {
    const uint32_t group = uint32_t(bytes[i]) << 16 | uint32_t(bytes[i + 1]) << 8 | bytes[i + 2];
    for (int shift = 18; shift >= 0; shift -= 6) out += kBase64Alphabet[(group >> shift) & 63];
  }
  // A final 1 or 2 bytes give 2 or 3 characters, padded with '=' to 4.
  if (const size_t rest = bytes.size() - i; rest > 0) {
    const uint32_t group = uint32_t(bytes[i]) << 16 | (rest == 2 ? uint32_t(bytes[i + 1]) << 8 : 0);
    out += kBase64Alphabet[(group >> 18) & 63];
    out += kBase64Alphabet[(group >> 12) & 63];
    out += rest == 2 ? kBase64Alphabet[(group >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

std::vector<uint8_t> encodePng(const InspectImage& image) {
  if (const std::string problem = imageProblem(image); !problem.empty())
    throw std::invalid_argument(problem);
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput memory(bytes);
  // The name only tells OpenImageIO the format; the bytes go to `memory`.
  auto writer = OIIO::ImageOutput::create("inspect.png", &memory);
  if (!writer) throw std::runtime_error("OpenImageIO has no PNG writer: " + OIIO::geterror());
  OIIO::ImageSpec spec(image.width, image.height, 4, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:UnassociatedAlpha", 1);  // the texels are stored as given
  const bool ok = writer->open("inspect.png", spec) &&
                  writer->write_image(OIIO::TypeDesc::UINT8, image.rgba.data()) && writer->close();
  if (!ok) throw std::runtime_error("image '" + image.name + "': " + writer->geterror());
  return bytes;
}

void writeInspectPage(const std::filesystem::path& file, const InspectRun& run) {
  if (run.frames.empty()) throw InputError(file, "the run has no frames");
  for (size_t f = 0; f < run.frames.size(); ++f)
    for (const InspectImage& image : run.frames[f].images)
      if (const std::string problem = imageProblem(image); !problem.empty())
        throw InputError(file, "frame " + std::to_string(f) + ": " + problem);

  json data = {{"title", run.title}, {"settings", pairsJson(run.settings)}};
  json& frames = data["frames"] = json::array();
  for (const InspectFrame& frame : run.frames) frames.push_back(frameJson(frame));
  // Invalid UTF-8 in a name becomes U+FFFD rather than failing the whole page.
  const std::string text = data.dump(-1, ' ', false, json::error_handler_t::replace);

  const size_t marker = kPageTemplate.find(kDataMarker);
  std::string page;
  page.reserve(kPageTemplate.size() + text.size() + text.size() / 16);
  page += kPageTemplate.substr(0, marker);
  appendScriptSafe(page, text);
  page += kPageTemplate.substr(marker + kDataMarker.size());
  writeFileAtomically(file, page);
}

}  // namespace vt
