// tinyobjloader compiled from its header into the OBJ fuzz program, so that libFuzzer's coverage
// and the sanitizers see inside the parser; its definitions take the place of Debian's
// uninstrumented libtinyobjloader in that program only.
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
