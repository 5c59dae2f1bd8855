#include "build/row_ring.h"

#include <algorithm>
#include <cstring>

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
    : side_(side),
      channels_(channels),
      capacity_(capacity),
      background_(background),
      stripOfColumn_((side + kStripTexels - 1) / kStripTexels, kNoStrip),
      written_(capacity) {}

void RowRing::append(uint64_t q) {
  if (q != rows_) throw std::logic_error("RowRing: rows must arrive in order");
  ++rows_;
  const uint64_t slot = q % capacity_;
  // The slot's previous row, q - capacity, wrote only into strips still in use: a strip is
  // retired below only once every row that wrote into it has been restored.
  for (const ColumnSpan& span : written_[slot])
    for (uint64_t x = span.begin; x < span.end;) {
      const uint64_t end = std::min(span.end, (x / kStripTexels + 1) * kStripTexels);
      fill(strips_[stripOfColumn_[x / kStripTexels]].data() +
               (slot * kStripTexels + x % kStripTexels) * channels_,
           end - x, channels_, background_);
      x = end;
    }
  written_[slot].clear();
  while (!writes_.empty() && writes_.front().second + capacity_ <= q) {
    const auto [strip, row] = writes_.front();
    writes_.pop_front();
    if (stripLastRow_[strip] != row) continue;  // written again later: a later entry retires it
    stripOfColumn_[stripColumn_[strip]] = kNoStrip;
    pool_.push_back(strip);
  }
}

void RowRing::declare(ColumnSpan span) {
  if (rows_ == 0 || span.begin >= span.end) return;
  const uint64_t q = rows_ - 1;
  std::vector<ColumnSpan>& spans = written_[q % capacity_];
  if (!spans.empty() && span.begin >= spans.back().begin && span.begin <= spans.back().end)
    spans.back().end = std::max(spans.back().end, span.end);
  else
    spans.push_back(span);
  for (uint64_t column = span.begin / kStripTexels; column <= (span.end - 1) / kStripTexels;
       ++column) {
    uint32_t& strip = stripOfColumn_[column];
    if (strip == kNoStrip) {
      if (pool_.empty()) {
        strip = static_cast<uint32_t>(strips_.size());
        strips_.emplace_back(stripBytes());
        fill(strips_.back().data(), capacity_ * kStripTexels, channels_, background_);
        stripColumn_.push_back(column);
        stripLastRow_.push_back(q);
      } else {
        strip = pool_.back();
        pool_.pop_back();
        stripColumn_[strip] = column;
      }
    } else if (stripLastRow_[strip] == q) {
      continue;  // already declared by this row
    }
    stripLastRow_[strip] = q;
    writes_.emplace_back(strip, q);
  }
}

uint8_t* RowRing::writable(uint64_t x) {
  const uint32_t strip = stripOfColumn_[x / kStripTexels];
  if (strip == kNoStrip || stripLastRow_[strip] + 1 != rows_)
    throw std::logic_error("RowRing: column " + std::to_string(x) + " was not declared");
  return strips_[strip].data() +
         (((rows_ - 1) % capacity_) * kStripTexels + x % kStripTexels) * channels_;
}

void RowRing::write(uint64_t x, const uint8_t* texels, uint64_t count) {
  for (uint64_t done = 0; done < count;) {
    const uint64_t run = std::min(count - done, kStripTexels - (x + done) % kStripTexels);
    std::memcpy(writable(x + done), texels + done * channels_, run * channels_);
    done += run;
  }
}

void RowRing::read(uint64_t q, uint64_t begin, uint64_t count, uint8_t* out) const {
  slotOf(q);  // throws unless held
  for (uint64_t done = 0; done < count;) {
    const uint64_t x = begin + done;
    const uint64_t run = std::min(count - done, kStripTexels - x % kStripTexels);
    if (stripOfColumn_[x / kStripTexels] == kNoStrip)
      fill(out + done * channels_, run, channels_, background_);
    else
      std::memcpy(out + done * channels_, texel(q, x), run * channels_);
    done += run;
  }
}

uint64_t RowRing::bytes() const {
  uint64_t spans = 0;
  for (const std::vector<ColumnSpan>& slot : written_) spans += slot.capacity();
  return strips_.size() * stripBytes() + stripOfColumn_.size() * sizeof(uint32_t) +
         spans * sizeof(ColumnSpan) + writes_.size() * sizeof(writes_.front());
}

}  // namespace vt
