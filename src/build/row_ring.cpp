#include "build/row_ring.h"

#include <algorithm>

namespace vt {
namespace {

void fill(uint8_t* texels, uint64_t count, uint32_t channels,
          const std::array<uint8_t, 4>& background) {
  for (uint64_t t = 0; t < count; ++t)
    for (uint32_t c = 0; c < channels; ++c) texels[t * channels + c] = background[c];
}

}  // namespace

RowRing::RowRing(uint64_t side, uint32_t channels, uint32_t capacity,
                 const std::array<uint8_t, 4>& background)
    : channels_(channels),
      rowBytes_(side * channels),
      capacity_(capacity),
      background_(background),
      texels_(rowBytes_ * capacity),
      written_(capacity) {
  fill(texels_.data(), side * capacity, channels, background);
}

uint8_t* RowRing::append(uint64_t q) {
  if (q != rows_) throw std::logic_error("RowRing: rows must arrive in order");
  ++rows_;
  uint8_t* slot = texels_.data() + (q % capacity_) * rowBytes_;
  for (const ColumnSpan& span : written_[q % capacity_])
    fill(slot + span.begin * channels_, span.end - span.begin, channels_, background_);
  written_[q % capacity_].clear();
  return slot;
}

void RowRing::wrote(ColumnSpan span) {
  std::vector<ColumnSpan>& spans = written_[(rows_ - 1) % capacity_];
  if (!spans.empty() && span.begin >= spans.back().begin && span.begin <= spans.back().end)
    spans.back().end = std::max(spans.back().end, span.end);
  else
    spans.push_back(span);
}

}  // namespace vt
