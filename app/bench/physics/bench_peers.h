// The peers `slime bench physics` runs beside the slime, each a program of its own built next to
// `slime` in bench/ (Bullet is linked into those programs only): peers/bullet_ball (the seed's skin in
// btSoftBody) and peers/bullet_tets (the slime's own tetrahedra in Bullet's finite-element solver).
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace slime {

// The peer program `name` (bullet_ball, bullet_tets): `configured` if given, else next to this
// program in bench/; empty if it is not built.
std::string findPeerProgram(const std::string& configured, const std::string& name);

// peers/bullet_ball for one drawn level (dropped 2 cm, fixed 1 ms steps, no grab), charged the CPU
// time of its whole process, set-up included. Null if the program failed.
nlohmann::json runBulletBall(const std::string& program, int level, double seconds);

// peers/bullet_tets for one body resolution: the same tetrahedra in Bullet's neo-Hookean FEM,
// dropped 2 cm, `seconds` simulated; its own CPU time per simulated ms (set-up excluded), the rest
// aspect, the volume and the inverted elements. Null if the program failed.
nlohmann::json runBulletTets(const std::string& program, int resolution, double seconds);

// A peer's front (bench_front.h): `program` run with `arguments` and --json FILE, the object it wrote
// ({"peer", "processor", "points": [...]}); null if it failed or wrote none.
nlohmann::json runPeerFront(const std::string& program, const std::vector<std::string>& arguments);

}  // namespace slime
