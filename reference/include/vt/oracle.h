#pragma once
// The virtual-texturing oracle: a bit-exact CPU reference for virtual-texture renderers (thesis
// 3.2.3). Open a texture, describe a scene and a cache state, render under a precision model,
// compare another renderer's frame or a capture with it.
//
//   #include <vt/oracle.h>
//   const vt::oracle::Texture texture = vt::oracle::Texture::open("scene.vt");
//   const vt::oracle::Capture capture = vt::oracle::readCapture("captures/frame0000.json");
//   const auto check = vt::oracle::checkCapture(capture, texture, vt::oracle::Profile::kGl45);
//   if (!check.comparison.passed()) ...
//
// Link with CMake's find_package(vt CONFIG) and target vt::vt, or pkg-config vt.

#include "vt/oracle/cache.h"
#include "vt/oracle/capture.h"
#include "vt/oracle/compare.h"
#include "vt/oracle/error.h"
#include "vt/oracle/render.h"
#include "vt/oracle/scene.h"
#include "vt/oracle/texture.h"
