// A solution's light sources by spectrum (MelanopicSources, radiosity/melanopic.hpp): each light
// group's spectrum and colour, and a gather of its own light when the scene has several.
#include "radiosity/error.hpp"
#include "radiosity/melanopic.hpp"
#include "radiosity/sensors.hpp"

#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>

namespace rad {

// Light of one spectrum and colour: the groups that emit it, and (when the scene has light of
// several) what gathers it alone.
struct MelanopicSources::Source {
    std::vector<std::size_t> groups; // into the solution's groups (empty: all the light)
    std::string names;               // theirs, for messages
    Spectrum spectrum;
    Rgb weights{0, 0, 0};
    radfmt::MeshData mesh;      // emission of this source's materials only
    std::vector<Rgb> radiosity; // its groups' radiosity summed
    std::optional<LuminaireSet> luminaires;
    std::unique_ptr<Gatherer> gatherer;
};

namespace {

struct GroupLight {
    std::string name;
    std::vector<std::uint32_t> materials; // an emitting-material group's materials
    bool luminaires = false;              // a group of the layout's luminaires
    Rgb tint{1, 1, 1};
    double cct = 0; // its lamps' colour temperature (K; 0: none given)
};

std::string text_of(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

// What emits each of the solution's groups, from the header's light_group.NAME fields
// ("luminaires of FILE", or "MAT=r,g,b MAT2=r,g,b").
std::vector<GroupLight> group_lights(const radfmt::MeshData& mesh,
                                     const radfmt::RadiosityData& solution,
                                     const radfmt::Header& header, const LuminaireSet* set) {
    std::vector<GroupLight> lights;
    for (const auto& name : solution.group_names) {
        GroupLight g{name, {}, false, {0, 0, 0}, 0};
        const auto* value = header.find("light_group." + name);
        if (value && value->rfind("luminaires of ", 0) == 0) {
            g.luminaires = true;
            bool first = true;
            for (const auto& l : set ? set->luminaires : std::vector<Luminaire>{}) {
                if (set->groups[set->group_of(l)] != name) continue;
                if (!first && (l.cct != g.cct))
                    throw InputError("light group '" + name + "' has luminaires of " +
                                     text_of(g.cct) + " K and " + text_of(l.cct) +
                                     " K: melanopic light needs one spectrum a group (give "
                                     "them groups of their own in the layout)");
                g.cct = l.cct, g.tint = l.tint, first = false;
            }
        } else if (value) {
            std::istringstream words(*value);
            std::string word;
            while (words >> word) {
                const auto material = word.substr(0, word.find('='));
                for (std::uint32_t m = 0; m < mesh.materials.size(); ++m)
                    if (mesh.materials[m].name == material) {
                        g.materials.push_back(m);
                        for (std::size_t c = 0; c < 3; ++c)
                            g.tint[c] += mesh.materials[m].emission[c];
                    }
            }
        }
        lights.push_back(std::move(g));
    }
    return lights;
}

std::string known_groups(const std::vector<GroupLight>& lights) {
    std::string names;
    for (const auto& g : lights) names += (names.empty() ? "" : ", ") + g.name;
    return names;
}

// Each group's spectrum: named in `specs`, else the one unnamed spec, else its lamps' CCT.
std::vector<Spectrum> group_spectra(const std::vector<GroupLight>& lights,
                                    const std::vector<std::string>& specs) {
    std::vector<std::optional<Spectrum>> chosen(lights.size());
    std::optional<Spectrum> every;
    for (const auto& spec : specs) {
        const auto eq = spec.find('=');
        std::size_t g = lights.size();
        if (eq != std::string::npos)
            for (g = 0; g < lights.size() && lights[g].name != spec.substr(0, eq);) ++g;
        if (eq == std::string::npos || (g == lights.size() && lights.empty())) {
            every = parse_spectrum(spec);
            continue;
        }
        if (g == lights.size())
            throw InputError("--spectrum " + spec + ": the solution has no light group '" +
                             spec.substr(0, eq) + "' (its groups: " + known_groups(lights) + ")");
        chosen[g] = parse_spectrum(spec.substr(eq + 1));
    }
    std::vector<Spectrum> spectra;
    for (std::size_t g = 0; g < lights.size(); ++g) {
        if (chosen[g])
            spectra.push_back(*chosen[g]);
        else if (every)
            spectra.push_back(*every);
        else if (lights[g].cct > 0)
            spectra.push_back(blackbody(lights[g].cct));
        else
            throw InputError("light group '" + lights[g].name +
                             "' has no spectrum to weigh its melanopic light by: give "
                             "--spectrum " +
                             lights[g].name +
                             "=SPEC (d65, a, cct:K or a CSV of wavelength_nm,value rows)" +
                             (lights[g].luminaires ? ", or the layout a cct column" : ""));
    }
    return spectra;
}

} // namespace

MelanopicSources::MelanopicSources(const radfmt::MeshData& mesh,
                                   const radfmt::RadiosityData& solution,
                                   const radfmt::Header& solution_header,
                                   const LuminaireSet* luminaires,
                                   const std::vector<std::string>& specs,
                                   const GatherOptions& options) {
    const auto lights = group_lights(mesh, solution, solution_header, luminaires);
    if (lights.empty()) { // no groups: one source, all the light
        if (specs.size() != 1 || specs[0].find('=') != std::string::npos)
            throw InputError("the solution has no light groups, so its light has one spectrum: "
                             "give --spectrum SPEC once (d65, a, cct:K or a CSV of "
                             "wavelength_nm,value rows)");
        auto s = std::make_unique<Source>();
        s->spectrum = parse_spectrum(specs[0]);
        Rgb tint{0, 0, 0};
        for (const auto& m : mesh.materials)
            for (std::size_t c = 0; c < 3; ++c) tint[c] += m.emission[c];
        if (!(luminous(tint) > 0)) tint = {1, 1, 1};
        s->weights = melanopic_weights(s->spectrum, tint);
        sources_.push_back(std::move(s));
        return;
    }
    const auto spectra = group_spectra(lights, specs);
    for (std::size_t g = 0; g < lights.size(); ++g) {
        const auto weights = melanopic_weights(spectra[g], lights[g].tint);
        Source* same = nullptr;
        for (auto& s : sources_)
            if (s->weights == weights) same = s.get();
        if (!same) {
            sources_.push_back(std::make_unique<Source>());
            same = sources_.back().get();
            same->spectrum = spectra[g], same->weights = weights;
        }
        same->groups.push_back(g);
        same->names += (same->names.empty() ? "" : ", ") + lights[g].name;
    }
    if (sources_.size() == 1) return; // the whole solution's gather is this source's
    for (auto& s : sources_) {
        s->mesh = mesh;
        std::vector<bool> emits(mesh.materials.size(), false);
        for (auto g : s->groups)
            for (auto m : lights[g].materials) emits[m] = true;
        for (std::size_t m = 0; m < mesh.materials.size(); ++m)
            if (!emits[m]) s->mesh.materials[m].emission = {0, 0, 0};
        s->radiosity.assign(mesh.patches.size(), {0, 0, 0});
        for (std::size_t i = 0; i < mesh.patches.size(); ++i)
            for (auto g : s->groups)
                for (std::size_t c = 0; c < 3; ++c)
                    s->radiosity[i][c] += solution.of_group(i, g)[c];
        if (luminaires) {
            s->luminaires = *luminaires;
            auto& kept = s->luminaires->luminaires;
            std::erase_if(kept, [&](const Luminaire& l) {
                const auto& name = luminaires->groups[luminaires->group_of(l)];
                for (auto g : s->groups)
                    if (lights[g].name == name) return false;
                return true;
            });
        }
        s->gatherer = std::make_unique<Gatherer>(s->mesh, s->radiosity, options);
    }
}

MelanopicSources::~MelanopicSources() = default;

MelanopicSources::Result MelanopicSources::at(const Irradiance& whole, const Vec3& position,
                                              const Vec3& direction, std::uint64_t index,
                                              const Box& scene_box) const {
    if (sources_.size() == 1) {
        const auto& w = sources_.front()->weights;
        return {melanopic_edi(whole.total(), w), melanopic_error(whole.error, w)};
    }
    Result r;
    double variance = 0;
    for (const auto& s : sources_) {
        std::string problem;
        const auto e = gather_sensor(*s->gatherer, s->luminaires ? &*s->luminaires : nullptr,
                                     scene_box, position, direction, index, problem);
        r.edi += melanopic_edi(e.total(), s->weights);
        const double error = melanopic_error(e.error, s->weights);
        variance += error * error;
    }
    r.error = std::sqrt(variance);
    return r;
}

std::vector<std::string> MelanopicSources::describe() const {
    std::vector<std::string> lines;
    for (const auto& s : sources_) {
        char text[160];
        std::snprintf(text, sizeof text, "%s (mel-DER %.4f)", s->spectrum.name.c_str(),
                      melanopic_der(s->spectrum));
        lines.push_back((s->names.empty() ? std::string("all the light") : s->names) + ": " + text);
    }
    return lines;
}

} // namespace rad
