// A GL shader program from vertex and fragment source, for the viewer's two drawers (the image blit
// and the panels' renderer). A shader that does not compile or a program that does not link throws,
// naming `what` and GL's log.
#pragma once

namespace slime {

unsigned linkShaderProgram(const char* vertexSource, const char* fragmentSource, const char* what);

}  // namespace slime
