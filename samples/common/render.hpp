// The engine, renderer and output the samples share with the command-line tool
// (tools/render/), under the names the samples use.
#pragma once

#include "render/vk.hpp"  // before any vkcollide header (see vk.hpp)

#include "render/engine.hpp"
#include "render/output.hpp"
#include "render/renderer.hpp"

namespace samples {

using render::Buffer;
using render::Camera;
using render::check;
using render::die;
using render::DrawId;
using render::Engine;
using render::EngineOptions;
using render::exitStatus;
using render::fail;
using render::FrameLog;
using render::framePath;
using render::Memory;
using render::msSince;
using render::objectColour;
using render::Renderer;
using render::Rgb;
using render::setProgramName;
using render::writePng;

}  // namespace samples
