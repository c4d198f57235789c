// Scene <-> bytes: fixed-width little-endian numbers, strings and vectors with a count first.
#include "import/scene_wire.hpp"

#include "radiosity/error.hpp"

#include <cstring>

namespace rad::import {

namespace {
class Writer {
  public:
    template <class T> void put(const T& value) {
        static_assert(std::is_trivially_copyable_v<T>);
        bytes_.append(reinterpret_cast<const char*>(&value), sizeof value);
    }
    void text(const std::string& s) {
        put<std::uint64_t>(s.size());
        bytes_.append(s);
    }
    void texts(const std::vector<std::string>& list) {
        put<std::uint64_t>(list.size());
        for (const auto& s : list) text(s);
    }
    std::string take() { return std::move(bytes_); }

  private:
    std::string bytes_;
};

class Reader {
  public:
    explicit Reader(std::string_view bytes) : bytes_(bytes) {}
    template <class T> T get() {
        T value;
        need(sizeof value);
        std::memcpy(&value, bytes_.data() + at_, sizeof value);
        at_ += sizeof value;
        return value;
    }
    // A count of items of at least `item_bytes` each: never more than the bytes left hold.
    std::size_t count(std::size_t item_bytes) {
        const auto n = get<std::uint64_t>();
        if (item_bytes > 0 && n > (bytes_.size() - at_) / item_bytes) fail();
        return static_cast<std::size_t>(n);
    }
    std::string text() {
        const auto n = count(1);
        std::string s(bytes_.substr(at_, n));
        at_ += n;
        return s;
    }
    std::vector<std::string> texts() {
        std::vector<std::string> list(count(8));
        for (auto& s : list) s = text();
        return list;
    }
    bool done() const { return at_ == bytes_.size(); }

  private:
    void need(std::size_t n) const {
        if (bytes_.size() - at_ < n) fail();
    }
    [[noreturn]] static void fail() {
        throw InternalError("the importer's child process sent a scene that does not decode");
    }
    std::string_view bytes_;
    std::size_t at_ = 0;
};

constexpr std::uint64_t kMagic = 0x5241442d53434e31ull; // "RAD-SCN1"
} // namespace

std::string encode_scene(const Scene& scene, const SceneReport& report) {
    Writer w;
    w.put(kMagic);
    w.text(scene.path);
    w.put<std::uint64_t>(scene.vertices.size());
    for (const auto& v : scene.vertices) w.put(v);
    w.put<std::uint64_t>(scene.polygons.size());
    for (const auto& p : scene.polygons) {
        w.put<std::uint64_t>(p.vertices.size());
        for (auto v : p.vertices) w.put(v);
        w.put(p.group);
        w.put(p.material);
        w.put(p.line);
        w.put(p.vn_sum);
    }
    w.texts(scene.groups);
    w.put<std::uint64_t>(scene.materials.size());
    for (const auto& m : scene.materials) {
        w.text(m.name);
        w.put(m.reflectance);
        w.put(m.emission);
        w.put(m.specular.kind);
        w.put(m.specular.reflectance);
        w.put(m.specular.transmittance);
        w.put(m.specular.ior);
        w.put(m.specular.roughness);
    }
    w.put<std::uint64_t>(scene.material_sources.size());
    for (const auto& s : scene.material_sources) {
        w.put(s.ambient);
        w.put(s.specular);
        w.put(s.transmittance);
        w.put(s.illum);
        w.put<std::uint8_t>(s.texture_missing);
    }
    w.texts(scene.material_files);
    w.put<std::uint64_t>(scene.face_ranges.size());
    for (const auto& r : scene.face_ranges) {
        w.put(r.first);
        w.text(r.origin);
    }
    w.put<std::uint64_t>(report.faces_defaulted);
    w.put(report.first_defaulted_line);
    w.text(report.default_material);
    for (const auto* list :
         {&report.unknown_materials, &report.missing_libraries, &report.libraries_found_by_name,
          &report.textures_averaged, &report.textures_replacing_kd, &report.texture_problems,
          &report.materials_read, &report.materials_changed, &report.lights})
        w.texts(*list);
    w.put<std::uint64_t>(report.dangling_corners);
    w.text(report.first_dangling);
    w.put(kMagic);
    return w.take();
}

void decode_scene(std::string_view bytes, Scene& scene, SceneReport& report) {
    Reader r(bytes);
    if (r.get<std::uint64_t>() != kMagic) r.count(~std::size_t(0)); // fails
    scene.path = r.text();
    scene.vertices.resize(r.count(sizeof(radfmt::Vec3)));
    for (auto& v : scene.vertices) v = r.get<radfmt::Vec3>();
    scene.polygons.resize(r.count(8));
    for (auto& p : scene.polygons) {
        p.vertices.resize(r.count(4));
        for (auto& v : p.vertices) v = r.get<std::uint32_t>();
        p.group = r.get<std::uint32_t>();
        p.material = r.get<std::uint32_t>();
        p.line = r.get<int>();
        p.vn_sum = r.get<radfmt::Vec3>();
    }
    scene.groups = r.texts();
    scene.materials.resize(r.count(8));
    for (auto& m : scene.materials) {
        m.name = r.text();
        m.reflectance = r.get<radfmt::Rgb>();
        m.emission = r.get<radfmt::Rgb>();
        m.specular.kind = r.get<radfmt::SpecularKind>();
        if (static_cast<std::uint32_t>(m.specular.kind) >= radfmt::kSpecularKinds)
            r.count(~std::size_t(0)); // fails
        m.specular.reflectance = r.get<radfmt::Rgb>();
        m.specular.transmittance = r.get<radfmt::Rgb>();
        m.specular.ior = r.get<double>();
        m.specular.roughness = r.get<double>();
    }
    scene.material_sources.resize(r.count(8));
    for (auto& s : scene.material_sources) {
        s.ambient = r.get<radfmt::Rgb>();
        s.specular = r.get<radfmt::Rgb>();
        s.transmittance = r.get<radfmt::Rgb>();
        s.illum = r.get<int>();
        s.texture_missing = r.get<std::uint8_t>() != 0;
    }
    scene.material_files = r.texts();
    scene.face_ranges.resize(r.count(8));
    for (auto& f : scene.face_ranges) {
        f.first = r.get<int>();
        f.origin = r.text();
    }
    report.faces_defaulted = r.get<std::uint64_t>();
    report.first_defaulted_line = r.get<int>();
    report.default_material = r.text();
    for (auto* list :
         {&report.unknown_materials, &report.missing_libraries, &report.libraries_found_by_name,
          &report.textures_averaged, &report.textures_replacing_kd, &report.texture_problems,
          &report.materials_read, &report.materials_changed, &report.lights})
        *list = r.texts();
    report.dangling_corners = r.get<std::uint64_t>();
    report.first_dangling = r.text();
    if (r.get<std::uint64_t>() != kMagic || !r.done()) r.count(~std::size_t(0));
}

} // namespace rad::import
