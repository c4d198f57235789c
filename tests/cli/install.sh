# The library as other projects use it: install to a temporary prefix, then build and run a
# small consumer that finds it with find_package(radiosity) and computes form factors of its
# own mesh (two facing unit squares one apart: F = 0.19982, Howell C-11).
source "$(dirname "$0")/lib.sh"
BUILD="$3"
cmake --install "$BUILD" --prefix "$TMP/prefix" >"$TMP/install.log" 2>&1 || { cat "$TMP/install.log"; fail "install"; }
[ -x "$TMP/prefix/bin/rad-ff" ] || fail "tools not installed"
[ -f "$TMP/prefix/include/radiosity/formfactor.hpp" ] || fail "headers not installed"
[ -s "$TMP/prefix/share/man/man1/rad-ff.1" ] || fail "man pages not installed"
[ -f "$TMP/prefix/include/radiosity/version.hpp" ] || fail "generated version header not installed"
grep -rl "CLI/CLI.hpp" "$TMP/prefix/include" && fail "an installed header includes CLI11"
# The dependency direction: only tools/ may use CLI11.
grep -rl "CLI/\|CLI11" "$SRC/libradiosity" "$SRC/formats" && fail "libradiosity or formats uses CLI11"
mkdir "$TMP/consumer"
cat > "$TMP/consumer/CMakeLists.txt" <<'CMAKE'
cmake_minimum_required(VERSION 3.25)
project(consumer CXX)
set(CMAKE_CXX_STANDARD 20)
find_package(radiosity 0.1 REQUIRED)
add_executable(consumer main.cpp)
target_link_libraries(consumer PRIVATE radiosity::radiosity)
CMAKE
cat > "$TMP/consumer/main.cpp" <<'CPP'
#include <radiosity/formfactor.hpp>
#include <radiosity/version.hpp>
#include <cstdio>
int main() {
    radfmt::MeshData mesh;
    mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    radfmt::Patch floor, ceiling;
    floor.corners = {0, 1, 2, 3};
    floor.area = 1, floor.centroid = {0.5, 0.5, 0}, floor.normal = {0, 0, 1};
    ceiling.corners = {4, 7, 6, 5};
    ceiling.area = 1, ceiling.centroid = {0.5, 0.5, 1}, ceiling.normal = {0, 0, -1};
    mesh.patches = {floor, ceiling};
    mesh.groups = {"all"};
    mesh.materials = {{"grey", {0.5, 0.5, 0.5}, {0, 0, 0}}};
    rad::FormFactorOptions options;
    options.quiet = true;
    const auto ff = rad::compute_form_factors(mesh, options);
    std::printf("%s %.5f %.5f\n", RADIOSITY_VERSION, ff.values.at(0),
                rad::parallel_rectangles_form_factor(1, 1, 1));
}
CPP
cmake -S "$TMP/consumer" -B "$TMP/consumer/build" -DCMAKE_PREFIX_PATH="$TMP/prefix" -DCMAKE_BUILD_TYPE=Release >"$TMP/consumer.log" 2>&1 \
  && cmake --build "$TMP/consumer/build" >>"$TMP/consumer.log" 2>&1 || { cat "$TMP/consumer.log"; fail "consumer build"; }
out=$("$TMP/consumer/build/consumer") || fail "consumer run"
python3 -c "import sys; v, f, exact = '$out'.split(); sys.exit(abs(float(f) - float(exact)) > 1e-3)" || fail "consumer form factor: $out"
finish
