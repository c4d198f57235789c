// Images out (and in, for tests): linear OpenEXR with provenance attributes, sRGB PNG
// previews, vertex-coloured PLY meshes.
#include "radiosity/image_io.hpp"

#include "radfmt/container.hpp"
#include "radiosity/error.hpp"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>

namespace rad {

void write_exr(const std::string& path, const Image& image,
               const std::map<std::string, std::string>& attributes,
               const std::vector<ImageLayer>& layers) {
    for (const auto& layer : layers)
        if (layer.image->width != image.width || layer.image->height != image.height)
            throw InternalError("EXR layer " + layer.name + " differs in size from the image");
    radfmt::write_atomically(path, [&](const std::filesystem::path& temp) {
        try {
            Imf::Header header(image.width, image.height);
            std::vector<std::pair<std::string, const Image*>> all{{"", &image}};
            for (const auto& layer : layers) all.emplace_back(layer.name + ".", layer.image);
            for (const auto& [prefix, img] : all)
                for (const char* name : {"R", "G", "B"})
                    header.channels().insert(prefix + name, Imf::Channel(Imf::FLOAT));
            for (const auto& [key, value] : attributes)
                header.insert(key, Imf::StringAttribute(value));
            Imf::OutputFile file(temp.c_str(), header);
            Imf::FrameBuffer fb;
            const std::size_t xs = 3 * sizeof(float), ys = xs * image.width;
            for (const auto& [prefix, img] : all) {
                char* base = reinterpret_cast<char*>(const_cast<float*>(img->rgb.data()));
                fb.insert(prefix + "R", Imf::Slice(Imf::FLOAT, base, xs, ys));
                fb.insert(prefix + "G", Imf::Slice(Imf::FLOAT, base + sizeof(float), xs, ys));
                fb.insert(prefix + "B", Imf::Slice(Imf::FLOAT, base + 2 * sizeof(float), xs, ys));
            }
            file.setFrameBuffer(fb);
            file.writePixels(image.height);
        } catch (const std::exception& e) {
            throw SystemError(path + ": cannot write EXR: " + e.what());
        }
    });
}

Image read_exr(const std::string& path, std::map<std::string, std::string>* attributes) {
    return read_exr_layer(path, "", attributes);
}

Image read_exr_layer(const std::string& path, const std::string& layer,
                     std::map<std::string, std::string>* attributes) {
    try {
        Imf::InputFile file(path.c_str());
        const std::string prefix = layer.empty() ? "" : layer + ".";
        if (!file.header().channels().findChannel(prefix + "R"))
            throw InputError(path + ": no layer '" + layer + "' in the image");
        const auto dw = file.header().dataWindow();
        Image image;
        image.width = dw.max.x - dw.min.x + 1;
        image.height = dw.max.y - dw.min.y + 1;
        image.rgb.assign(static_cast<std::size_t>(image.width) * image.height * 3, 0.0f);
        Imf::FrameBuffer fb;
        char* base = reinterpret_cast<char*>(image.rgb.data());
        const std::size_t xs = 3 * sizeof(float), ys = xs * image.width;
        base -= (dw.min.x * xs + dw.min.y * ys);
        fb.insert(prefix + "R", Imf::Slice(Imf::FLOAT, base, xs, ys));
        fb.insert(prefix + "G", Imf::Slice(Imf::FLOAT, base + sizeof(float), xs, ys));
        fb.insert(prefix + "B", Imf::Slice(Imf::FLOAT, base + 2 * sizeof(float), xs, ys));
        file.setFrameBuffer(fb);
        file.readPixels(dw.min.y, dw.max.y);
        if (attributes)
            for (auto it = file.header().begin(); it != file.header().end(); ++it)
                if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
                    (*attributes)[it.name()] = s->value();
        return image;
    } catch (const InputError&) {
        throw;
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

namespace {
// 0.85 over the luminance that 99% of the area of the patches `counted` stays below; 0 when
// none of them is lit.
double exposure_of(const radfmt::MeshData& solved, const std::vector<Rgb>& radiosity,
                   bool with_emitters) {
    std::vector<std::pair<double, double>> lit; // luminance, area
    double total = 0;
    for (std::size_t i = 0; i < solved.patches.size() && i < radiosity.size(); ++i) {
        const auto& p = solved.patches[i];
        if (!with_emitters && solved.materials[p.material].emits()) continue;
        const auto& b = radiosity[i];
        const double y = 0.2126 * b[0] + 0.7152 * b[1] + 0.0722 * b[2];
        if (!(y > 0) || !(p.area > 0)) continue;
        lit.emplace_back(y, p.area);
        total += p.area;
    }
    if (lit.empty()) return 0;
    std::sort(lit.begin(), lit.end());
    double below = 0;
    for (const auto& [y, area] : lit)
        if ((below += area) >= 0.99 * total) return 0.85 / y;
    return 0.85 / lit.back().first;
}
} // namespace

double solution_exposure(const radfmt::MeshData& solved, const std::vector<Rgb>& radiosity) {
    // A scene whose every lit patch emits (a light box, an all-emitting test object) is
    // exposed for its emitters, the same way, rather than left to each image.
    const double without = exposure_of(solved, radiosity, false);
    return without > 0 ? without : exposure_of(solved, radiosity, true);
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
    write_png_rgb8(path, image.width, image.height, pixels);
}

void write_png_rgb8(const std::string& path, int width, int height,
                    const std::vector<std::uint8_t>& pixels) {
    radfmt::write_atomically(path, [&](const std::filesystem::path& temp) {
        png_image png{};
        png.version = PNG_IMAGE_VERSION;
        png.width = static_cast<png_uint_32>(width);
        png.height = static_cast<png_uint_32>(height);
        png.format = PNG_FORMAT_RGB;
        // Through our own FILE: libpng's write_to_file removes the file when a write fails,
        // and the file may be a device (/dev/full) written in place.
        std::FILE* file = std::fopen(temp.c_str(), "wb");
        if (!file) throw SystemError(path + ": cannot open for writing: " + std::strerror(errno));
        const bool encoded = png_image_write_to_stdio(&png, file, 0, pixels.data(), 0, nullptr);
        bool written = std::fflush(file) == 0;
        int error = errno;
        if (std::fclose(file) != 0 && written) written = false, error = errno;
        if (!encoded) throw SystemError(path + ": cannot write PNG: " + png.message);
        if (!written) throw SystemError(path + ": cannot write PNG: " + std::strerror(error));
    });
}

std::vector<std::uint8_t> encode_png_rgb8(int width, int height,
                                          const std::vector<std::uint8_t>& pixels) {
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    png.width = static_cast<png_uint_32>(width);
    png.height = static_cast<png_uint_32>(height);
    png.format = PNG_FORMAT_RGB;
    png_alloc_size_t bytes = 0;
    // First call sizes the buffer, the second fills it.
    if (!png_image_write_to_memory(&png, nullptr, &bytes, 0, pixels.data(), 0, nullptr))
        throw InternalError(std::string("cannot encode PNG: ") + png.message);
    std::vector<std::uint8_t> out(bytes);
    if (!png_image_write_to_memory(&png, out.data(), &bytes, 0, pixels.data(), 0, nullptr))
        throw InternalError(std::string("cannot encode PNG: ") + png.message);
    out.resize(bytes);
    return out;
}

void write_ply(const std::string& path, const radfmt::MeshData& mesh, const CornerColours& corners,
               double exposure) {
    radfmt::write_atomically(path, [&](const std::filesystem::path& temp) {
        std::ofstream out(temp);
        std::size_t vertex_count = 0;
        for (const auto& p : mesh.patches) vertex_count += std::size_t(p.corner_count());
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
            const auto ids = mesh.corners(i);
            for (std::size_t k = 0; k < ids.size(); ++k) {
                const auto& v = mesh.vertices[ids[k]];
                const auto& c = corners.at(mesh, i, k);
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
        out.close(); // a full disk may only show when the last bytes go out
        if (out.fail()) throw SystemError(path + ": cannot write PLY: " + std::strerror(errno));
    });
}

} // namespace rad
