#include "eval/inspect_page.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string_view>

#include "common/error.h"
#include "common/posix_file.h"
#include "eval/inspect_page_html.h"
#include "eval/inspect_page_js.h"

namespace vt {
namespace {

// The page around the data (src/eval/inspect_page.html and .js, embedded at build time). Everything
// is drawn by the script from the JSON, with textContent, so no string of the run is ever parsed
// as HTML. kScriptMarker is replaced by the script, kDataMarker by the run's JSON.
constexpr std::string_view kDataMarker = "@INSPECT_DATA@";
constexpr std::string_view kScriptMarker = "@INSPECT_SCRIPT@";


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

// Queue rows are arrays [page, level, x, y, priority, streamed, term values...] under the
// queue's term names, the union of the requests' terms in order of first appearance (null where a
// request lacks one): a queue has thousands of rows, and names once per queue keep the page small.
json queueJson(const InspectQueue& queue) {
  std::vector<std::string> terms;
  for (const InspectRequest& request : queue.queue)
    for (const InspectTerm& term : request.terms)
      if (std::find(terms.begin(), terms.end(), term.name) == terms.end())
        terms.push_back(term.name);
  json rows = json::array();
  for (const InspectRequest& request : queue.queue) {
    json row = {request.page, request.level,    request.x,
                request.y,    request.priority, request.streamed};
    std::vector<json> values(terms.size());  // null where the request has no such term
    for (const InspectTerm& term : request.terms)
      values[std::find(terms.begin(), terms.end(), term.name) - terms.begin()] = term.value;
    for (json& value : values) row.push_back(std::move(value));
    rows.push_back(std::move(row));
  }
  return {{"label", queue.label},
          {"terms", terms},
          {"queue", std::move(rows)},
          {"streamed", queue.streamed}};
}

json frameJson(const InspectFrame& frame) {
  json images = json::array();
  for (const InspectImage& image : frame.images)
    images.push_back({{"name", image.name},
                      {"width", image.width},
                      {"height", image.height},
                      {"src", "data:image/png;base64," + encodeBase64(encodePng(image))}});
  json queues = json::array();
  for (const InspectQueue& queue : frame.queues) queues.push_back(queueJson(queue));
  return {{"frame", frame.frame},
          {"statistics", pairsJson(frame.statistics)},
          {"images", std::move(images)},
          {"queues", std::move(queues)}};
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

  const std::string_view html = kInspectPageHtml, script = kInspectPageScript;
  const size_t dataMarker = html.find(kDataMarker), scriptMarker = html.find(kScriptMarker);
  std::string page;
  page.reserve(html.size() + script.size() + text.size() + text.size() / 16);
  page += html.substr(0, dataMarker);
  appendScriptSafe(page, text);
  page += html.substr(dataMarker + kDataMarker.size(),
                      scriptMarker - dataMarker - kDataMarker.size());
  page += script;
  page += html.substr(scriptMarker + kScriptMarker.size());
  writeFileAtomically(file, page);
}

}  // namespace vt
