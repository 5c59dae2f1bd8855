#pragma once
// The one exception the oracle's API throws: bad input (a damaged texture file, a malformed
// capture, frames of different sizes), with a message that names the file or argument and what
// was wrong, e.g. "frame0003.json: needbuffer image is 320 x 199, the viewport 320 x 200".

#include <stdexcept>
#include <string>

#include "vt/oracle/export.h"

namespace vt::oracle {

class VT_ORACLE_API Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message);
  ~Error() override;
};

}  // namespace vt::oracle
