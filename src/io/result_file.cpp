#include "luxtrace/io/result_file.hpp"

#include "luxtrace/io/atomic_file.hpp"
#include "luxtrace/io/file_seal.hpp"
#include "luxtrace/scene/scene.hpp"
#include "result_parts.hpp"

namespace luxtrace {

void write_result(const std::filesystem::path& path, const Scene& scene, const TallyLayout& layout,
                  std::span<const std::uint64_t> tallies, const RunInfo& info, const ResultEstimates& estimates,
                  const std::vector<HistoryRow>& history, const CheckpointData* checkpoint) {
    using namespace result_parts;
    // The first kSealBytes are kept for luxtrace's seal (file_seal.hpp).
    std::vector<char> image = hdf5::file_image(path, kSealBytes, [&](hid_t file) {
        write_run_info(file, scene, layout, tallies, info, checkpoint != nullptr);
        write_mesh(file, scene);
        write_surface_map(file, scene, layout, tallies, estimates);
        write_detectors(file, scene, layout, tallies, estimates);
        write_observers(file, scene, layout, tallies, estimates);
        // An annual run's groups are its sky patches and suns: /annual holds them.
        if (!scene.annual) write_light_groups(file, scene, layout, tallies);
        write_light_scenes(file, scene, estimates);
        if (!scene.annual) write_daylight(file, scene);
        write_annual(file, scene, layout, tallies, estimates);
        write_history(file, history, info);
        if (checkpoint != nullptr) write_checkpoint(file, layout, *checkpoint);
    });
    seal_image(image);
    write_file_atomically(path, image);
}

}  // namespace luxtrace
