// tinyobjloader compiled from Debian's header into the scene library instead of linking its shared
// library: programs built from the drawing parts (vt-capture) then carry no C++ library of another
// build, and the fuzz and sanitizer builds see inside the parser.
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
