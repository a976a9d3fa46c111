#include "luxtrace/io/result_file.hpp"

#include "luxtrace/io/file_seal.hpp"
#include "luxtrace/scene/scene.hpp"
#include "result_parts.hpp"

namespace luxtrace {

namespace result_parts {

void write_all(hid_t file, const Scene& scene, const TallyLayout& layout, std::span<const std::uint64_t> tallies,
               const RunInfo& info, const ResultEstimates& estimates, const std::vector<HistoryRow>& history,
               const CheckpointData* checkpoint) {
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
}

void write_tally_checkpoint(hid_t file, const Scene& scene, const TallyLayout& layout, const RunInfo& info,
                            const std::vector<HistoryRow>& history, const CheckpointData& checkpoint) {
    write_run_info(file, scene, layout, checkpoint.tallies, info, true);
    write_history(file, history, info);
    write_checkpoint(file, layout, checkpoint);
}

}  // namespace result_parts

namespace {

// The first kSealBytes are kept for luxtrace's seal (file_seal.hpp).
std::vector<char> sealed_image(const std::filesystem::path& path, const std::function<void(hid_t)>& fill) {
    std::vector<char> image = hdf5::file_image(path, kSealBytes, fill);
    seal_image(image);
    return image;
}

}  // namespace

std::vector<char> result_image(const std::filesystem::path& path, const Scene& scene, const TallyLayout& layout,
                               std::span<const std::uint64_t> tallies, const RunInfo& info,
                               const ResultEstimates& estimates, const std::vector<HistoryRow>& history,
                               const CheckpointData* checkpoint) {
    return sealed_image(path, [&](hid_t file) {
        result_parts::write_all(file, scene, layout, tallies, info, estimates, history, checkpoint);
    });
}

std::vector<char> tally_checkpoint_image(const std::filesystem::path& path, const Scene& scene,
                                         const TallyLayout& layout, const RunInfo& info,
                                         const std::vector<HistoryRow>& history, const CheckpointData& checkpoint) {
    return sealed_image(path, [&](hid_t file) {
        result_parts::write_tally_checkpoint(file, scene, layout, info, history, checkpoint);
    });
}

}  // namespace luxtrace
