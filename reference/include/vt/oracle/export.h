#pragma once
// Marks what the shared library libvt exports: the public API and nothing else (the oracle's
// internals are linked in but hidden, so they cannot clash with an engine's own symbols).

#if defined(VT_ORACLE_BUILDING_SHARED)
#define VT_ORACLE_API __attribute__((visibility("default")))
#else
#define VT_ORACLE_API
#endif
