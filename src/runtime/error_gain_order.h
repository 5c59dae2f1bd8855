#pragma once
// Ancestor streaming by expected error removed (docs/streaming.md, "Beyond the thesis"): the
// needed pages and their missing ancestors, each priced by the error its arrival removes from the
// pixels that would fall back to something coarser, and ordered greedily, each page priced again
// once those before it are in.
//
// The error of a needed page q shown through its ancestor on level l, E_q(l), is either the sum
// of the NoiseValues (thesis 3.3.1.2: each page against its upsampled parent) from q up to, not
// including, level l (`gain`, noiseValueSums), or the error `vt build --ancestor-errors` measured
// through that ancestor (`gain_ssim`). An error is never counted below that of a finer ancestor
// (E_q is made non-increasing toward q: max over the levels from l to q's), so that every gain
// is >= 0 and only falls as pages are added. A page a on level L(a) above q's resident level e_q
// brings q from
// E_q(e_q) down to E_q(L(a)), so its gain is
//   gain(a) = sum over needed pages q in a's subtree with e_q < L(a) of w_q (E_q(e_q) - E_q(L(a)))
// with w_q the heuristic's value of q (its pixels, say). Once a is in, every such q has
// e_q = L(a), so ancestors of pages already brought nearer gain less and a parent that serves
// four children at once can come before each of them. Gains only fall as pages are added, so the
// greedy order is computed lazily (a page is priced again only when it reaches the top). Pages
// whose gain is zero (flat pages, NoiseValue 0) follow, by the summed weight of their subtree's
// needed pages; ties go to the smaller absolute index.

#include <cstdint>
#include <map>
#include <vector>

#include "runtime/page_priority.h"
#include "runtime/page_table.h"

namespace vt {

// `weight`: the needed, non-resident pages (absolute index) and their heuristic value. Returns
// them and their missing ancestors in greedy order, each with the gain it had when it was taken.
std::vector<StreamRequest> orderByErrorGain(const std::map<uint64_t, double>& weight,
                                            const PageTable& table, const AncestorErrors& error);

// E_q(l) as the sum of the NoiseValues from q up to, not including, level l.
AncestorErrors noiseValueSums(const NoiseValues& noise);

}  // namespace vt
