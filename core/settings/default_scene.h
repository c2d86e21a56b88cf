// The default scene (assets/default.json), embedded into the program at build time.
#pragma once

#include <string_view>

namespace slime {

std::string_view defaultSceneJson();

}  // namespace slime
