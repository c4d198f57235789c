#include "radiosity/shade.hpp"

#include "radfmt/container.hpp"
#include "radiosity/cli.hpp"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <png.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

namespace rad {

namespace {
constexpr double kDeg = std::numbers::pi / 180;
}

View parse_view(const std::string& text, const std::string& source, View view) {
    std::istringstream in(text);
    std::string word;
    auto number = [&](const std::string& option) {
        std::string token;
        double value = 0;
        if (!(in >> token)) throw InputError(source + ": " + option + " needs a number");
        if (!parse_number(token, value))
            throw InputError(source + ": " + option + ": '" + token + "' is not a number");
        if (!std::isfinite(value)) throw InputError(source + ": " + option + " must be finite");
        return value;
    };
    auto vector = [&](const std::string& option) {
        const double x = number(option), y = number(option), z = number(option);
        return Vec3{x, y, z};
    };
    while (in >> word) {
        if (word == "rvu" || word == "-vtv" || word.rfind("#", 0) == 0) continue;
        if (word == "-vp")
            view.position = vector(word);
        else if (word == "-vd")
            view.direction = vector(word);
        else if (word == "-vu")
            view.up = vector(word);
        else if (word == "-vh")
            view.horizontal_deg = number(word);
        else if (word == "-vv")
            view.vertical_deg = number(word);
        else
            throw InputError(source + ": unknown view option '" + word +
                             "' (use -vp -vd -vu -vh -vv)");
    }
    if (length(view.direction) == 0) throw InputError(source + ": view direction -vd is zero");
    if (length(cross(view.direction, view.up)) <= 1e-9 * length(view.direction) * length(view.up))
        throw InputError(source + ": view up -vu is zero or parallel to the direction -vd");
    for (double angle : {view.horizontal_deg, view.vertical_deg})
        if (!(angle > 0 && angle < 180))
            throw InputError(source +
                             ": view angles -vh and -vv must be between 0 and 180 degrees");
    return view;
}

View read_view_file(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw InputError(path + ": cannot open view file");
    std::string line, all;
    int number = 0;
    View view;
    while (std::getline(in, line)) {
        ++number;
        const auto hash = line.find('#');
        if (hash != std::string::npos) line = line.substr(0, hash);
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        view = parse_view(line, path + ":" + std::to_string(number), view);
    }
    return view;
}

Smoothing parse_smoothing(const std::string& name) {
    if (name == "flat") return Smoothing::Flat;
    if (name == "average") return Smoothing::Average;
    if (name == "area") return Smoothing::Area;
    if (name == "crease") return Smoothing::Crease;
    throw InputError("unknown smoothing '" + name + "' (use average, area, crease or flat)");
}

std::vector<std::array<Rgb, 4>> corner_colours(const radfmt::MeshData& mesh,
                                               const std::vector<Rgb>& patch, Smoothing mode,
                                               double crease_deg) {
    const std::size_t n = mesh.patches.size();
    std::vector<std::array<Rgb, 4>> out(n);
    if (mode == Smoothing::Flat) {
        for (std::size_t i = 0; i < n; ++i) out[i].fill(patch[i]);
        return out;
    }
    std::vector<std::vector<std::uint32_t>> around(mesh.vertices.size());
    for (std::size_t i = 0; i < n; ++i)
        for (int k = 0; k < mesh.patches[i].corner_count(); ++k)
            around[mesh.patches[i].corners[k]].push_back(static_cast<std::uint32_t>(i));
    const double cos_crease = std::cos(crease_deg * kDeg);
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
        const auto& p = mesh.patches[i];
        for (int k = 0; k < p.corner_count(); ++k) {
            Rgb sum{0, 0, 0};
            double weight = 0;
            for (auto q : around[p.corners[k]]) {
                const auto& pq = mesh.patches[q];
                if (mode == Smoothing::Crease &&
                    (pq.material != p.material || dot(pq.normal, p.normal) < cos_crease))
                    continue;
                const double w = mode == Smoothing::Average ? 1.0 : pq.area;
                for (int c = 0; c < 3; ++c) sum[c] += w * patch[q][c];
                weight += w;
            }
            for (int c = 0; c < 3; ++c) out[i][k][c] = weight > 0 ? sum[c] / weight : patch[i][c];
        }
        if (p.corner_count() == 3) out[i][3] = out[i][2];
    });
    return out;
}

namespace {

struct ScreenVertex {
    double x, y;  // pixel coordinates of the supersampled frame
    double inv_z; // 1 / depth, interpolated linearly in screen space
    Rgb colour_over_z;
};

struct ScreenTriangle {
    std::array<ScreenVertex, 3> v;
    double min_y, max_y;
};

} // namespace

Image render(const radfmt::MeshData& mesh, const std::vector<std::array<Rgb, 4>>& corners,
             const View& view, int width, int height, int supersampling) {
    const int ss = std::max(1, supersampling);
    const int W = width * ss, H = height * ss;
    const Vec3 dir = normalized(view.direction);
    const Vec3 right = normalized(cross(dir, view.up));
    const Vec3 up = cross(right, dir);
    const double tan_h = std::tan(0.5 * view.horizontal_deg * kDeg),
                 tan_v = std::tan(0.5 * view.vertical_deg * kDeg);
    double extent = 0;
    for (const auto& v : mesh.vertices) extent = std::max(extent, length(v - view.position));
    const double near = std::max(1e-9, 1e-5 * extent);

    struct CamPoint {
        Vec3 p; // camera space: x right, y up, z depth
        Rgb c;
    };
    std::vector<ScreenTriangle> triangles;
    for (std::size_t i = 0; i < mesh.patches.size(); ++i) {
        const auto& patch = mesh.patches[i];
        std::vector<CamPoint> poly;
        for (int k = 0; k < patch.corner_count(); ++k) {
            const Vec3 d = mesh.vertices[patch.corners[k]] - view.position;
            poly.push_back({{dot(d, right), dot(d, up), dot(d, dir)}, corners[i][k]});
        }
        // Clip against the near plane so geometry behind the eye never projects.
        std::vector<CamPoint> clipped;
        for (std::size_t k = 0; k < poly.size(); ++k) {
            const auto& a = poly[k];
            const auto& b = poly[(k + 1) % poly.size()];
            if (a.p[2] >= near) clipped.push_back(a);
            if ((a.p[2] >= near) != (b.p[2] >= near)) {
                const double t = (near - a.p[2]) / (b.p[2] - a.p[2]);
                CamPoint m;
                m.p = a.p + (b.p - a.p) * t;
                for (int c = 0; c < 3; ++c) m.c[c] = a.c[c] + (b.c[c] - a.c[c]) * t;
                clipped.push_back(m);
            }
        }
        if (clipped.size() < 3) continue;
        std::vector<ScreenVertex> screen;
        for (const auto& cp : clipped) {
            const double inv_z = 1.0 / cp.p[2];
            ScreenVertex sv;
            sv.x = (cp.p[0] * inv_z / tan_h + 1) * 0.5 * W;
            sv.y = (1 - cp.p[1] * inv_z / tan_v) * 0.5 * H;
            sv.inv_z = inv_z;
            for (int c = 0; c < 3; ++c) sv.colour_over_z[c] = cp.c[c] * inv_z;
            screen.push_back(sv);
        }
        for (std::size_t k = 1; k + 1 < screen.size(); ++k) {
            ScreenTriangle t{{screen[0], screen[k], screen[k + 1]}, 0, 0};
            t.min_y = std::min({t.v[0].y, t.v[1].y, t.v[2].y});
            t.max_y = std::max({t.v[0].y, t.v[1].y, t.v[2].y});
            if (t.max_y < 0 || t.min_y > H) continue;
            triangles.push_back(t);
        }
    }

    std::vector<float> hi(static_cast<std::size_t>(W) * H * 3, 0.0f);
    std::vector<double> depth(static_cast<std::size_t>(W) * H, 0.0); // stores 1/z; 0 = empty
    const int band = 16;
    tbb::parallel_for(0, (H + band - 1) / band, [&](int b) {
        const int y0 = b * band, y1 = std::min(H, y0 + band);
        for (const auto& t : triangles) {
            if (t.max_y < y0 || t.min_y > y1) continue;
            const auto &a = t.v[0], &bb = t.v[1], &c = t.v[2];
            const double area = (bb.x - a.x) * (c.y - a.y) - (bb.y - a.y) * (c.x - a.x);
            if (std::abs(area) < 1e-12) continue;
            const int ya = std::max(y0, static_cast<int>(std::floor(t.min_y)));
            const int yb = std::min(y1 - 1, static_cast<int>(std::ceil(t.max_y)));
            const int xa = std::max(0, static_cast<int>(std::floor(std::min({a.x, bb.x, c.x}))));
            const int xb = std::min(W - 1, static_cast<int>(std::ceil(std::max({a.x, bb.x, c.x}))));
            for (int y = ya; y <= yb; ++y)
                for (int x = xa; x <= xb; ++x) {
                    const double px = x + 0.5, py = y + 0.5;
                    const double w0 = ((bb.x - px) * (c.y - py) - (bb.y - py) * (c.x - px)) / area;
                    const double w1 = ((c.x - px) * (a.y - py) - (c.y - py) * (a.x - px)) / area;
                    const double w2 = 1 - w0 - w1;
                    // A small tolerance: the two triangles beside a shared edge compute it in
                    // opposite orders, and rounding must not leave a crack between them.
                    if (w0 < -1e-9 || w1 < -1e-9 || w2 < -1e-9) continue;
                    const double inv_z = w0 * a.inv_z + w1 * bb.inv_z + w2 * c.inv_z;
                    const std::size_t at = static_cast<std::size_t>(y) * W + x;
                    if (inv_z <= depth[at]) continue;
                    depth[at] = inv_z;
                    for (int ch = 0; ch < 3; ++ch)
                        hi[3 * at + ch] = static_cast<float>((w0 * a.colour_over_z[ch] +
                                                              w1 * bb.colour_over_z[ch] +
                                                              w2 * c.colour_over_z[ch]) /
                                                             inv_z);
                }
        }
    });

    Image image;
    image.width = width;
    image.height = height;
    image.rgb.assign(static_cast<std::size_t>(width) * height * 3, 0.0f);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            double sum[3] = {0, 0, 0};
            bool covered = false;
            for (int sy = 0; sy < ss; ++sy)
                for (int sx = 0; sx < ss; ++sx) {
                    const std::size_t at =
                        static_cast<std::size_t>(y * ss + sy) * W + (x * ss + sx);
                    covered = covered || depth[at] > 0;
                    for (int c = 0; c < 3; ++c) sum[c] += hi[3 * at + c];
                }
            image.covered_pixels += covered;
            for (int c = 0; c < 3; ++c)
                image.rgb[3 * (static_cast<std::size_t>(y) * width + x) + c] =
                    static_cast<float>(sum[c] / (ss * ss));
        }
    return image;
}

void write_exr(const std::string& path, const Image& image,
               const std::map<std::string, std::string>& attributes) {
    radfmt::write_atomically(path, [&](const std::filesystem::path& temp) {
        try {
            Imf::Header header(image.width, image.height);
            for (const char* name : {"R", "G", "B"})
                header.channels().insert(name, Imf::Channel(Imf::FLOAT));
            for (const auto& [key, value] : attributes)
                header.insert(key, Imf::StringAttribute(value));
            Imf::OutputFile file(temp.c_str(), header);
            Imf::FrameBuffer fb;
            char* base = reinterpret_cast<char*>(const_cast<float*>(image.rgb.data()));
            const std::size_t xs = 3 * sizeof(float), ys = xs * image.width;
            fb.insert("R", Imf::Slice(Imf::FLOAT, base, xs, ys));
            fb.insert("G", Imf::Slice(Imf::FLOAT, base + sizeof(float), xs, ys));
            fb.insert("B", Imf::Slice(Imf::FLOAT, base + 2 * sizeof(float), xs, ys));
            file.setFrameBuffer(fb);
            file.writePixels(image.height);
        } catch (const std::exception& e) {
            throw InputError(path + ": cannot write EXR: " + e.what());
        }
    });
}

Image read_exr(const std::string& path, std::map<std::string, std::string>* attributes) {
    try {
        Imf::InputFile file(path.c_str());
        const auto dw = file.header().dataWindow();
        Image image;
        image.width = dw.max.x - dw.min.x + 1;
        image.height = dw.max.y - dw.min.y + 1;
        image.rgb.assign(static_cast<std::size_t>(image.width) * image.height * 3, 0.0f);
        Imf::FrameBuffer fb;
        char* base = reinterpret_cast<char*>(image.rgb.data());
        const std::size_t xs = 3 * sizeof(float), ys = xs * image.width;
        base -= (dw.min.x * xs + dw.min.y * ys);
        fb.insert("R", Imf::Slice(Imf::FLOAT, base, xs, ys));
        fb.insert("G", Imf::Slice(Imf::FLOAT, base + sizeof(float), xs, ys));
        fb.insert("B", Imf::Slice(Imf::FLOAT, base + 2 * sizeof(float), xs, ys));
        file.setFrameBuffer(fb);
        file.readPixels(dw.min.y, dw.max.y);
        if (attributes)
            for (auto it = file.header().begin(); it != file.header().end(); ++it)
                if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
                    (*attributes)[it.name()] = s->value();
        return image;
    } catch (const std::exception& e) {
        throw InputError(path + ": cannot read EXR: " + e.what());
    }
}

double auto_exposure(const Image& image) {
    std::vector<float> luminance;
    for (std::size_t i = 0; i + 2 < image.rgb.size(); i += 3) {
        const float y =
            0.2126f * image.rgb[i] + 0.7152f * image.rgb[i + 1] + 0.0722f * image.rgb[i + 2];
        if (y > 0) luminance.push_back(y);
    }
    if (luminance.empty()) return 1;
    const auto at = luminance.begin() + static_cast<long>(0.95 * (luminance.size() - 1));
    std::nth_element(luminance.begin(), at, luminance.end());
    return *at > 0 ? 0.8 / *at : 1;
}

std::uint8_t to_srgb8(double linear) {
    linear = std::clamp(linear, 0.0, 1.0);
    const double s =
        linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1 / 2.4) - 0.055;
    return static_cast<std::uint8_t>(std::lround(s * 255));
}

void write_png(const std::string& path, const Image& image, double exposure) {
    std::vector<std::uint8_t> pixels(image.rgb.size());
    for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = to_srgb8(image.rgb[i] * exposure);
    radfmt::write_atomically(path, [&](const std::filesystem::path& temp) {
        png_image png{};
        png.version = PNG_IMAGE_VERSION;
        png.width = static_cast<png_uint_32>(image.width);
        png.height = static_cast<png_uint_32>(image.height);
        png.format = PNG_FORMAT_RGB;
        if (!png_image_write_to_file(&png, temp.c_str(), 0, pixels.data(), 0, nullptr))
            throw InputError(path + ": cannot write PNG: " + png.message);
    });
}

void write_ply(const std::string& path, const radfmt::MeshData& mesh,
               const std::vector<std::array<Rgb, 4>>& corners, double exposure) {
    radfmt::write_atomically(path, [&](const std::filesystem::path& temp) {
        std::ofstream out(temp);
        std::size_t vertex_count = 0;
        for (const auto& p : mesh.patches) vertex_count += p.corner_count();
        // Each patch corner gets its own vertex: crease-aware smoothing gives one vertex
        // different colours on different sides of an edge.
        out << "ply\nformat ascii 1.0\ncomment radiosity rad-shade: colours are smoothed "
               "radiosity, sRGB\n"
            << "element vertex " << vertex_count
            << "\nproperty float x\nproperty float y\nproperty float z\n"
            << "property uchar red\nproperty uchar green\nproperty uchar blue\n"
            << "property float radiosity_r\nproperty float radiosity_g\nproperty float "
               "radiosity_b\n"
            << "element face " << mesh.patches.size()
            << "\nproperty list uchar int vertex_indices\nend_header\n";
        out.precision(9);
        for (std::size_t i = 0; i < mesh.patches.size(); ++i) {
            const auto& p = mesh.patches[i];
            for (int k = 0; k < p.corner_count(); ++k) {
                const auto& v = mesh.vertices[p.corners[k]];
                const auto& c = corners[i][k];
                out << v[0] << ' ' << v[1] << ' ' << v[2] << ' ' << int(to_srgb8(c[0] * exposure))
                    << ' ' << int(to_srgb8(c[1] * exposure)) << ' '
                    << int(to_srgb8(c[2] * exposure)) << ' ' << c[0] << ' ' << c[1] << ' ' << c[2]
                    << '\n';
            }
        }
        std::size_t next = 0;
        for (const auto& p : mesh.patches) {
            out << p.corner_count();
            for (int k = 0; k < p.corner_count(); ++k) out << ' ' << next++;
            out << '\n';
        }
        if (!out.flush()) throw InputError(path + ": cannot write PLY");
    });
}

} // namespace rad
