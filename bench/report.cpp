#include "report.hpp"

#include "timing.hpp"

#include <algorithm>
#include <cstdio>

namespace luxtrace::bench {

void print_report(const Measurements& m, const MeasurePlan& plan, std::size_t floor_rays) {
    const std::vector<int>& thread_counts = plan.thread_counts;
    const std::vector<Series>& series = m.series;
    const std::uint64_t photons = plan.photons;
    std::printf("tracer: %llu rays per run (%.3f per photon); tally checksum %016llx, identical in all %zu runs\n\n",
                static_cast<unsigned long long>(m.tracer_rays), double(m.tracer_rays) / double(photons),
                static_cast<unsigned long long>(m.tally_checksum), thread_counts.size() * plan.repeats);
    // tracer/replay: ratio of the medians; paired: median of the ratios measured back to
    // back. busy: CPU / (wall x threads) of replay runs, and of the tracer runs' tracing
    // threads over their tracing time (RunSummary::tracing_busy).
    std::printf("threads | replay Mrays/s          | cosine Mrays/s | tracer Mrays/s          | tracer/replay | paired "
                "| busy\n");
    std::printf("--------+-------------------------+----------------+-------------------------+---------------+--------"
                "+-----\n");
    auto lo = [](const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); };
    auto hi = [](const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); };
    for (std::size_t ti = 0; ti < thread_counts.size(); ++ti) {
        const Series& se = series[ti];
        std::printf("%7d | %6.3f [%6.3f..%6.3f] | %14.3f | %6.3f [%6.3f..%6.3f] | %12.1f%% | %5.1f%% | %3.0f%%\n",
                    thread_counts[ti], median(se.replay) * 1e-6, lo(se.replay) * 1e-6, hi(se.replay) * 1e-6,
                    median(se.cosine) * 1e-6, median(se.tracer) * 1e-6, lo(se.tracer) * 1e-6, hi(se.tracer) * 1e-6,
                    100.0 * median(se.tracer) / median(se.replay), 100.0 * median(se.paired), 100.0 * median(se.busy));
    }
    if (plan.packets)
        for (std::size_t ti = 0; ti < thread_counts.size(); ++ti)
            std::printf("packets, %d thread(s): rtcIntersect8 on the same rays in groups of 8 consecutive ones: "
                        "%.1f%% of rtcIntersect1's rate (paired median; same hits)\n",
                        thread_counts[ti], 100.0 * median(series[ti].packets));
    if (plan.floor)
        for (std::size_t ti = 0; ti < thread_counts.size(); ++ti) {
            const Series& se = series[ti];
            std::printf("floor, %d thread(s): %.3f Mrays/s (%.3f rays/photon), replay of its rays %.3f Mrays/s: "
                        "floor/replay %.1f%% (paired %.1f%%)\n",
                        thread_counts[ti], median(se.floor) * 1e-6, double(floor_rays) / double(photons),
                        median(se.floor_replay) * 1e-6, 100.0 * median(se.floor) / median(se.floor_replay),
                        100.0 * median(se.floor_paired));
        }
    for (std::size_t i = 1; i < series.size(); ++i) {
        std::vector<double> tr, rp;
        for (int rep = 0; rep < plan.repeats; ++rep) {
            tr.push_back(series[i].tracer[rep] / series[0].tracer[rep]);
            rp.push_back(series[i].replay[rep] / series[0].replay[rep]);
        }
        std::printf("speed-up %d/%d threads: tracer %.2fx (paired %.2fx), replay %.2fx (paired %.2fx)\n",
                    thread_counts[i], thread_counts[0], median(series[i].tracer) / median(series[0].tracer), median(tr),
                    median(series[i].replay) / median(series[0].replay), median(rp));
    }
}

}  // namespace luxtrace::bench
