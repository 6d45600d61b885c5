// wavepath-kernel-programs SCENE...: every OpenCL program the renderers can
// build for the scenes, found by asking the renderers themselves
// (wavefront_program, megakernel_program) for each combination of the
// choices that change a program, and printed once each, one a line:
//
//   KIND<TAB>FILES<TAB>OPTIONS<TAB>WHAT
//
// KIND is "gpu-default" for what `wavepath render SCENE` builds on a GPU
// with either backend (the scene as in its file, no flags), else "variant";
// FILES are the program's kernel files (space-separated names in kernels/),
// compiled as one program; OPTIONS what build_program gives the OpenCL
// compiler (compiler_options); WHAT the first combination that builds it,
// and how many more do. A combination the renderer refuses (lanes the
// compaction cannot take, Embree on a GPU or with sppm, the megakernel for
// sppm) is no program.
//
// The choices: the scene's render settings as in its file, and with each of
// the command line's overrides that change the kernels' options alone
// (--nee, --mis, --hemisphere, --sampler, --integrator); a GPU and a CPU
// device (their defaults of lanes, intersector, shadow stage and
// intersect_and_shade differ: the CPU's give the other stage sets); and the
// backends' options on the command line (--compaction, --lanes,
// --intersector, and the film's sums of squares, which --target-error and
// --adaptive turn on). Not varied: WavefrontOptions' shadow_stage,
// intersect_and_shade and specialise, which only the API sets (tests).
// tests/gpu_compile/compile_for_gpus.py compiles what it prints for GPU
// targets (docs/architecture.md, "GPU targets").
#include <iostream>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli/errors.h"
#include "cli/options.h"
#include "megakernel/megakernel_renderer.h"
#include "opencl/device.h"
#include "wavefront/intersector_choice.h"
#include "wavefront/wavefront_renderer.h"

namespace wp {
namespace {

struct Listed {
    std::string what;  // the first combination that builds it
    int combinations = 0;
    bool gpu_default = false;  // what `wavepath render SCENE` builds on a GPU, for a scene as in its file
};

class ProgramList {
 public:
    void add(const KernelProgram& program, const std::string& what, bool gpu_default) {
        std::string files;
        for (const std::string& file : program.files) files += (files.empty() ? "" : " ") + file;
        const std::string key = files + "\t" + compiler_options(program.options);
        auto [at, added] = programs_.try_emplace(key, Listed{what, 0});
        if (added) order_.push_back(key);
        ++at->second.combinations;
        at->second.gpu_default = at->second.gpu_default || gpu_default;
    }
    void print(std::ostream& out) const {
        for (const std::string& key : order_) {
            const Listed& listed = programs_.at(key);
            out << (listed.gpu_default ? "gpu-default" : "variant") << "\t" << key << "\t" << listed.what;
            if (listed.combinations > 1) out << " (and " << listed.combinations - 1 << " more)";
            out << "\n";
        }
    }
    std::size_t size() const { return order_.size(); }

 private:
    std::map<std::string, Listed> programs_;
    std::vector<std::string> order_;  // as found, so that the output is stable
};

// A device of each kind, as the renderers' choices see it (their type and
// preferred float vector width: opencl/lanes.h, wavefront/intersector_choice.h).
DeviceInfo simulated_device(const std::string& type, unsigned preferred_float_vector_width) {
    DeviceInfo device;
    device.name = "a simulated " + type;
    device.type = type;
    device.preferred_float_vector_width = device.native_float_vector_width = preferred_float_vector_width;
    return device;
}

// The render flags that change the kernels' options, one at a time ("": the scene as in its file).
struct Override {
    std::string flag;
    cli::RenderOverrides overrides;
};
std::vector<Override> kernel_overrides() {
    std::vector<Override> list{{"", {}}};
    auto add = [&](const std::string& flag, const std::string& value,
                   std::optional<std::string> cli::RenderOverrides::*member) {
        Override o{flag + " " + value, {}};
        o.overrides.*member = value;
        list.push_back(o);
    };
    for (const char* value : {"on", "off"}) add("--nee", value, &cli::RenderOverrides::nee);
    for (const char* value : {"on", "off"}) add("--mis", value, &cli::RenderOverrides::mis);
    for (const char* value : {"cosine", "uniform"}) add("--hemisphere", value, &cli::RenderOverrides::hemisphere);
    for (const char* value : {"sobol", "independent"}) add("--sampler", value, &cli::RenderOverrides::sampler);
    for (const char* value : {"path", "sppm"}) add("--integrator", value, &cli::RenderOverrides::integrator);
    return list;
}

std::string on_off(bool on) { return on ? "on" : "off"; }

// Calls `add(program, description)` for each program a renderer builds for
// `scene` on `device` with some combination of the command line's options
// that change a program.
template <class Add>
void list_for_scene(const Scene& scene, const DeviceInfo& device, Add add) {
    for (bool film_squares : {false, true}) {
        for (unsigned lanes : {0u, 1u, 4u, 8u, 16u}) {  // 0: the renderer's default
            const std::string common = " --lanes " + std::to_string(lanes) + ", film squares " + on_off(film_squares);
            MegakernelOptions megakernel;
            megakernel.lanes = lanes;
            megakernel.film_squares = film_squares;
            try {
                add(megakernel_program(scene, megakernel, device), "megakernel" + common);
            } catch (const std::invalid_argument&) {
                // a combination the megakernel refuses
            }
            for (Compaction compaction : {Compaction::Atomic, Compaction::Scan})
                for (std::optional<Intersector> intersector :
                     {std::optional<Intersector>(), std::optional(Intersector::Bvh),
                      std::optional(Intersector::Embree)}) {
                    WavefrontOptions wavefront;
                    wavefront.lanes = lanes;
                    wavefront.film_squares = film_squares;
                    wavefront.compaction = compaction;
                    wavefront.intersector = intersector;
                    try {
                        add(wavefront_program(scene, wavefront, device),
                            std::string("wavefront --compaction ") +
                                (compaction == Compaction::Scan ? "scan" : "atomic") + " --intersector " +
                                (intersector ? intersector_name(*intersector) : "default") + common);
                    } catch (const std::invalid_argument&) {
                        // a combination the wavefront refuses
                    } catch (const DeviceError&) {
                        // Embree on a device that is not a CPU
                    }
                }
        }
    }
}

int run(int argc, char** argv) {
    if (argc < 2) {
        std::cerr << "usage: wavepath-kernel-programs SCENE...\n";
        return 2;
    }
    const DeviceInfo gpu = simulated_device("GPU", 1), cpu = simulated_device("CPU", 16);
    ProgramList programs;
    for (int i = 1; i < argc; ++i) {
        const std::string path = argv[i];
        const Scene loaded = load_scene(path);
        // What `wavepath render SCENE` builds on a GPU, with either backend.
        programs.add(wavefront_program(loaded, {}, gpu), path + " on a GPU: wavefront, its defaults", true);
        try {
            programs.add(megakernel_program(loaded, {}, gpu), path + " on a GPU: megakernel, its defaults", true);
        } catch (const std::invalid_argument&) {
            // a scene the megakernel cannot render
        }
        for (const Override& o : kernel_overrides()) {
            Scene scene = loaded;
            try {
                cli::apply_overrides(o.overrides, scene);
            } catch (const cli::UsageError&) {
                continue;  // e.g. sppm on a scene it cannot render
            }
            for (const DeviceInfo& device : {gpu, cpu})
                list_for_scene(scene, device, [&](const KernelProgram& program, const std::string& description) {
                    programs.add(
                        program,
                        path + (o.flag.empty() ? "" : " " + o.flag) + " on a " + device.type + ": " + description,
                        false);
                });
        }
    }
    programs.print(std::cout);
    return programs.size() > 0 ? 0 : 1;
}

}  // namespace
}  // namespace wp

int main(int argc, char** argv) {
    try {
        return wp::run(argc, argv);
    } catch (const std::exception& e) {
        std::cerr << "wavepath-kernel-programs: " << e.what() << "\n";
        return 1;
    }
}
