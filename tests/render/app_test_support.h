// The viewer application as the app tests drive it: hidden window, no vsync, no recent-files file.
#pragma once

#include <doctest/doctest.h>

#include <memory>
#include <string>

#include "app/viewer_app.h"
#include "pipeline/level_limits.h"

namespace polarview {

// Levels are made ahead only where a test asks for it (prepareNextLevel): the others wait for
// nothing they do not look at.
inline std::unique_ptr<ViewerApp> makeHiddenApp(int width = 640, int height = 400, size_t faceBudget = kDefaultFaceBudget,
                                                bool prepareNextLevel = false) {
  ViewerOptions options;
  options.prepareNextLevel = prepareNextLevel;
  options.width = width;
  options.height = height;
  options.hidden = true;
  options.persistRecent = false;
  options.vsync = false;
  options.faceBudget = faceBudget;
  auto app = std::make_unique<ViewerApp>(options);
  std::string error;
  REQUIRE_MESSAGE(app->init(&error), error);
  return app;
}

}  // namespace polarview
