#include "luxtrace/run/run_loop.hpp"

#include "luxtrace/annual/annual_grid.hpp"

#include "luxtrace/core/error.hpp"
#include "luxtrace/estimate/gather_factors.hpp"
#include "luxtrace/estimate/result_estimates.hpp"
#include "luxtrace/io/annual_ladybug.hpp"
#include "luxtrace/io/atomic_file.hpp"
#include "luxtrace/io/sensor_table.hpp"
#include "luxtrace/run/direct_pass.hpp"
#include "luxtrace/run/reduction_message.hpp"
#include "luxtrace/run/write_steps.hpp"
#include "luxtrace/scene/scene.hpp"
#include "luxtrace/stats/estimates.hpp"
#include "luxtrace/stats/global_sums.hpp"
#include "luxtrace/tally/message_packing.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <ostream>
#include <thread>

#ifndef LUXTRACE_VERSION
#define LUXTRACE_VERSION "unknown"
#endif

namespace luxtrace {

namespace {

bool is_input_error(const std::exception_ptr& e) {
    try {
        std::rethrow_exception(e);
    } catch (const InputError&) {
        return true;
    } catch (...) {
        return false;
    }
}

std::string describe(const std::exception_ptr& e) {
    try {
        std::rethrow_exception(e);
    } catch (const std::exception& x) {
        return x.what();
    } catch (...) {
        return "unknown exception";
    }
}

// Items of at most 1M photons, at least 8 per rank when the budget is small.
std::uint64_t item_block(std::uint64_t photons, int ranks) {
    return std::clamp<std::uint64_t>(photons / (8 * static_cast<std::uint64_t>(ranks)) + 1, std::uint64_t{4096},
                                     std::uint64_t{1} << 20);
}

// Reductions at photon counts: each rank stops handing out photons at its share of the
// next count, and the snapshot is taken when all its threads have parked there.
std::uint64_t fence_step_of(const RunConfig& run, int ranks) {
    return run.report_every_photons > 0
               ? std::max<std::uint64_t>(1, (run.report_every_photons + ranks - 1) / static_cast<std::uint64_t>(ranks))
               : 0;
}

// The sides each rank owns, by rank (message_packing.hpp).
std::vector<MessagePart> every_rank_sides(const TallyLayout& layout, int ranks) {
    std::vector<MessagePart> parts;
    for (int r = 0; r < ranks; ++r) parts.push_back(owned_sides(layout, r, ranks));
    return parts;
}

// The scene's annual_indirect_tag, which a checkpoint must match (empty without [annual]).
std::string indirect_tag(const Scene& scene) {
    if (!scene.annual) return {};
    const AnnualOptions& o = scene.annual->options;
    return annual_indirect_tag(o.indirect, o.gather_rays, o.gather_patch_m);
}

// The ranks share casting the gather's rays (GatherShare), as they share the year's skies.
GatherShare gather_share(const Communicator& comm) {
    GatherShare share;
    share.part = comm.rank();
    share.parts = comm.size();
    share.gather = [&comm](std::vector<double>& values, const std::vector<std::size_t>& offsets) {
        comm.allgather_parts(values, offsets);
    };
    return share;
}

}  // namespace

RunLoop::RunLoop(const Scene& scene, const Communicator& comm, const RunOptions& opt, std::ostream& out)
    : scene_(scene), run_(scene.run), comm_(comm), opt_(opt), out_(out), t0_(comm.wtime()), ranks_(comm.size()),
      threads_(opt.threads > 0 ? opt.threads : available_cores()), layout_(tally_layout(scene)), store_(layout_),
      restored_(opt.restart.empty()
                    ? RestartState{}
                    : restore_checkpoint(opt.restart, run_, layout_, scene.light_groups, indirect_tag(scene))),
      plan_(restored_.done, run_.photons, item_block(run_.photons, ranks_), ranks_), work_(plan_, comm.rank()),
      embree_(opt.embree != nullptr ? *opt.embree : own_embree_.emplace(scene)),
      surfaces_(scene, embree_, gather_share(comm)),
      checkpoint_path_(run_.checkpoint.empty() ? run_.output + ".checkpoint.h5" : run_.checkpoint),
      show_(comm.is_root() && !opt.quiet),
      tty_(show_ && ::isatty(STDOUT_FILENO) != 0 && std::getenv("OMPI_COMM_WORLD_SIZE") == nullptr),
      fence_step_(fence_step_of(run_, ranks_)), totals_(layout_.size()), parts_(every_rank_sides(layout_, ranks_)),
      own_(parts_[static_cast<std::size_t>(comm.rank())]), lit_(mask_side_words(layout_), 0),
      requests_(global_requests(scene)), own_replicate_photons_(layout_.replicates(), 0),
      period_s_(RunController::initial_period_s(run_)) {
    // A checkpoint's tallies enter the first reduction as rank 0's counts.
    if (!opt.restart.empty()) {
        if (comm.is_root()) store_.assign(restored_.tallies);
        std::vector<std::uint64_t>().swap(restored_.tallies);
    }
    if (comm.is_root())
        control_.emplace(scene, layout_, std::move(restored_.history), restored_.elapsed_s,
                         plan_.previously_done_count());
    summary_.output = run_.output;
    info_.luxtrace_version = LUXTRACE_VERSION;
    info_.scene_file = std::filesystem::absolute(scene.file).string();
    info_.seed = run_.seed;
    info_.ranks = ranks_;
    info_.threads_per_rank = threads_;
    info_.sampler = run_.sampler;
    info_.photon_layout = kPhotonLayout;
    info_.load_s = opt.load_s;  // this rank's; the result takes the slowest rank's (write)
    info_.bvh_build_s = embree_.build_s();
}

void RunLoop::check_writable() {
    std::vector<double> writable{1.0};
    std::string not_writable;
    if (comm_.is_root()) {
        try {
            luxtrace::check_writable(run_.output, "result file");
            luxtrace::check_writable(checkpoint_path_, "checkpoint");
            for (const std::filesystem::path& table : sensor_table_paths(scene_, run_.output))
                luxtrace::check_writable(table, "sensor table");
        } catch (const IoError& e) {
            not_writable = e.what();
            writable[0] = 0.0;
        }
    }
    comm_.broadcast(writable);
    if (writable[0] == 0.0) throw InputError(not_writable);
}

void RunLoop::trace() {
    // Once the output is known to be writable, and before the tracing's clock starts.
    if (show_ && !surfaces_.gather().empty())
        out_ << "the gather's rays at the annual grids: " << std::fixed << std::setprecision(2)
             << surfaces_.gather().build_s() << " s (" << surfaces_.gather().cells() << " sensors, shared by " << ranks_
             << " rank(s))\n"
             << std::defaultfloat << std::flush;
    if (scene_.annual && scene_.annual->options.shadow_rays()) {
        const double d0 = comm_.wtime();
        annual_direct_ = annual_direct_pass(scene_, embree_, comm_);
        for (std::size_t det = 0; det < annual_direct_.size(); ++det)
            if (layout_.gathered(det)) {
                DirectCoefficients& d = annual_direct_[det];
                d.gather_unit_lx_per_lm = surfaces_.gather().unit_lx_per_lm();
                d.gather_rel_var.assign(d.cells, 0.0F);  // update_gather_errors
            }
        if (show_)
            out_ << "direct light by shadow rays at the annual grids: " << std::fixed << std::setprecision(2)
                 << comm_.wtime() - d0 << " s\n"
                 << std::defaultfloat << std::flush;
    }
    fence_ = fence_step_;
    if (fence_step_ > 0) work_.set_fence(fence_);
    TraceOptions topt;
    topt.seed = run_.seed;
    topt.sampler = run_.sampler;
    topt.replicates = run_.replicates;
    topt.threads = threads_;
    topt.chunk = 256;  // pause latency: a thread finishes its chunk before parking
    trace0_ = comm_.wtime();
    pool_.emplace(scene_, embree_, surfaces_, store_, work_, topt);
}

void RunLoop::wait_for_reduction() {
    const double due = comm_.wtime() + period_s_;
    while (comm_.wtime() < due && !pool_->exhausted() && !pool_->failed() &&
           !(opt_.signal != nullptr && opt_.signal->load() != 0) && !(fence_step_ > 0 && work_.fence_reached()))
        pool_->wait_for_park(std::min(0.005, std::max(0.0, due - comm_.wtime())));
}

void RunLoop::encode_snapshot(bool signalled, bool idle) {
    // The threads add to the store's other array from here on: `delta_` holds what they
    // added since the previous reduction.
    delta_ = store_.take();
    ReductionMessage m;
    m.progress.resize(static_cast<std::size_t>(ranks_));
    m.progress[static_cast<std::size_t>(comm_.rank())] = work_.progress();
    m.flags.signalled = signalled ? 1 : 0;
    m.flags.idle = idle ? 1 : 0;
    if (pool_->failed()) (is_input_error(pool_->error()) ? m.flags.input_fault : m.flags.internal_fault) = 1;
    for (std::size_t r = 0; r < own_replicate_photons_.size(); ++r)
        own_replicate_photons_[r] += delta_[layout_.replicate_photons(r)];
    m.replicate_photons = own_replicate_photons_;
    header_ = std::move(m);
}

void RunLoop::snapshot() {
    const double s0 = comm_.wtime();
    // Threads park at chunk boundaries with their buffers flushed: the store and the
    // progress agree exactly.
    pool_->pause();
    encode_snapshot(opt_.signal != nullptr && opt_.signal->load() != 0, pool_->exhausted());
    if (fence_step_ > 0) work_.set_fence(fence_ += fence_step_);
    pool_->resume();
    stall_s_ = comm_.wtime() - s0;
    stall_total_s_ += stall_s_;
    ++reductions_;
}

PendingReduce RunLoop::start_reduce() {
    const std::span<const std::uint64_t> delta = delta_;
    if (ranks_ == 1) {
        // The rank owns every word: its counts go straight into the totals.
        if (totals_empty_) {
            // The totals are still zero: the counts become them as they are (the store
            // gets the totals' untouched array back), marking the sides with counts.
            const std::vector<std::uint64_t> marks = message_mask(layout_, delta);
            for (std::size_t w = 0; w < lit_.size(); ++w) lit_[w] |= marks[w];
            store_.exchange_taken(totals_);
            totals_empty_ = false;
        } else add_and_clear(layout_, delta_, totals_.span(), lit_);
        summed_header_ = header_;
        return PendingReduce::completed();
    }
    // The counts every rank sent since the previous reduction fit 32-bit words, with room
    // for their sum over the ranks, unless some rank says otherwise (RankFlags::wide).
    std::uint64_t map_bits = 0;
    mask_ = message_mask(layout_, delta, MessagePart::whole(layout_), &map_bits);
    const std::uint64_t bound = opt_.narrow_word_bound > 0
                                    ? opt_.narrow_word_bound
                                    : (std::uint64_t{1} << 32) / static_cast<std::uint64_t>(ranks_);
    header_.flags.wide = map_bits >= bound ? 1 : 0;
    timed_wait([&] { comm_.allreduce_or(mask_); });
    for (std::size_t w = 0; w < lit_.size(); ++w) lit_[w] |= mask_[w];
    std::vector<std::uint64_t> words;
    header_.encode(words);
    timed_wait([&] { comm_.allreduce_sum(words); });
    summed_header_ = ReductionMessage::decode(words, ranks_, layout_.replicates());
    const bool wide = summed_header_.flags.wide > 0;
    // Every owner's part of the map, in rank order, then the head and the tail for rank 0.
    part_counts_.clear();
    std::size_t map_words = 0;
    for (const MessagePart& p : parts_)
        map_words += part_counts_.emplace_back(packed_size(layout_, mask_, layout_.size(), p));
    const MessagePart head_tail = MessagePart::head_and_tail_only();
    tail_send_.resize(packed_size(layout_, mask_, layout_.size(), head_tail));
    take_part(layout_, mask_, delta_, head_tail, tail_send_.data());
    auto pack_map = [&](auto& send) {
        send.resize(map_words);
        auto* out = send.data();
        for (const MessagePart& p : parts_) out = take_part(layout_, mask_, delta_, p, out);
    };
    if (wide) pack_map(map_send64_);
    else pack_map(map_send32_);
    info_.reduction_message_words = std::max(info_.reduction_message_words, map_words + tail_send_.size());
    info_.reduction_message_bytes = std::max(info_.reduction_message_bytes,
                                             map_words * (wide ? 8 : 4) + tail_send_.size() * 8);
    PendingReduce tail = comm_.ireduce_sum_to_root(tail_send_, tail_recv_);
    PendingReduce map = wide ? comm_.ireduce_scatter_sum(map_send64_, part_counts_, map_recv64_)
                             : comm_.ireduce_scatter_sum(map_send32_, part_counts_, map_recv32_);
    return PendingReduce::both(std::move(map), std::move(tail));
}

void RunLoop::finish_reduce() {
    if (ranks_ > 1) {
        if (summed_header_.flags.wide > 0)
            add_packed_part<std::uint64_t>(layout_, mask_, own_, map_recv64_, totals_.span());
        else add_packed_part<std::uint32_t>(layout_, mask_, own_, map_recv32_, totals_.span());
        if (comm_.is_root())
            add_packed_part<std::uint64_t>(layout_, mask_, MessagePart::head_and_tail_only(), tail_recv_,
                                           totals_.span());
    }
    // Every rank knows the photons, and each replicate's (which the sides' replicate
    // spread reads from the tallies' last words).
    photons_ = count_photons(plan_.done_ranges(summed_header_.progress));
    for (std::size_t r = 0; r < layout_.replicates(); ++r)
        totals_[layout_.replicate_photons(r)] = summed_header_.replicate_photons[r];
    estimate_owned_sides();
}

void RunLoop::estimate_owned_sides() {
    // Each rank sums its own chunks of sides (its fronts', then its backs') for every
    // global estimate asked for; rank 0 adds all chunks in chunk order (global_sums.hpp:
    // the same bits on any rank count).
    const double e0 = photons_ > 0 ? scene_.lights.total_flux_lm() / static_cast<double>(photons_) : 0.0;
    const std::size_t C = chunk_count(layout_), Q = requests_.weights.size(), K = GlobalSums::kWords;
    std::vector<double> words(own_.chunks() * Q * K);
    for (std::size_t q = 0; q < Q; ++q) {
        const WeightedTallies w(layout_, totals_.span(), requests_.weights[q]);
        std::size_t c = 0;
        for (const ChunkRange& range : {own_.fronts, own_.backs})
            for (const GlobalSums& sums : chunk_sums(w, scene_.triangle_area_m2, e0, photons_, range, lit_))
                sums.to_words(words.data() + (c++ * Q + q) * K);
    }
    std::vector<double> all;
    if (ranks_ > 1) {
        std::vector<std::size_t> counts;
        for (const MessagePart& p : parts_) counts.push_back(p.chunks() * Q * K);
        timed_wait([&] { comm_.gather_to_root(std::span<const double>(words), counts, all); });
    } else all = std::move(words);
    if (!comm_.is_root()) return;
    // `all` holds each rank's chunks in rank order: put them in chunk order.
    std::vector<std::size_t> at(C);
    std::size_t k = 0;
    for (const MessagePart& p : parts_)
        for (const ChunkRange& range : {p.fronts, p.backs})
            for (std::size_t c = range.begin; c < range.end; ++c) at[c] = k++;
    globals_.clear();
    for (std::size_t q = 0; q < Q; ++q) {
        std::vector<GlobalSums> chunks(C);
        for (std::size_t c = 0; c < C; ++c) chunks[c] = GlobalSums::from_words(all.data() + (at[c] * Q + q) * K);
        globals_.push_back(global_estimate(chunks, layout_.replicates() > 0));
    }
}

void RunLoop::gather_map() {
    if (ranks_ == 1) return;
    // Each rank's lit sides, OR-ed: every rank then knows every part's length.
    std::vector<std::uint64_t> mask = message_mask(layout_, totals_.span(), own_);
    comm_.allreduce_or(mask);
    std::vector<std::size_t> counts;
    for (const MessagePart& p : parts_) counts.push_back(packed_size(layout_, mask, layout_.size(), p));
    std::vector<std::uint64_t> mine(counts[static_cast<std::size_t>(comm_.rank())]), all;
    pack_part(layout_, mask, totals_.span(), own_, mine.data());
    comm_.gather_to_root(std::span<const std::uint64_t>(mine), counts, all);
    if (!comm_.is_root()) return;
    std::size_t at = counts[0];
    for (int r = 1; r < ranks_; ++r) {
        const std::size_t n = counts[static_cast<std::size_t>(r)];
        unpack_part(layout_, mask, parts_[static_cast<std::size_t>(r)],
                    std::span<const std::uint64_t>(all).subspan(at, n), totals_.span());
        at += n;
    }
}

// A step of the shared annual post-processing on this rank: after the first failure the
// later steps are skipped (the rank still takes part in every message).
struct RunLoop::PartAttempt {
    bool failed = false;
    std::string error;
    template <class F>
    void operator()(F&& f) {
        if (failed) return;
        try {
            f();
        } catch (const std::exception& e) {
            failed = true;
            error = e.what();
        }
    }
};

void RunLoop::update_gather_errors(double e0) {
    if (!comm_.is_root() || !layout_.any_gathered()) return;
    const GatherTable& g = surfaces_.gather();
    const std::span<const std::uint64_t> totals = totals_.span();
    // Each site's irradiance from its arrivals, and each cell's gathered light with it.
    std::vector<double> site_lx(g.sites()), arrivals(g.sites());
    for (std::size_t i = 0; i < site_lx.size(); ++i) {
        arrivals[i] = static_cast<double>(totals[layout_.gather_site(i)]);
        site_lx[i] = e0 * arrivals[i] / g.site_area_m2(i);
    }
    for (std::size_t det = 0; det < annual_direct_.size(); ++det) {
        if (!layout_.gathered(det)) continue;
        DirectCoefficients& d = annual_direct_[det];
        std::vector<double> gathered_lx(d.cells, 0.0);
        const double per_unit = e0 * d.gather_unit_lx_per_lm;
        for (std::size_t grp = 0; grp < layout_.groups(); ++grp)
            for (std::size_t c = 0; c < d.cells; ++c)
                gathered_lx[c] += per_unit * static_cast<double>(totals[layout_.detector_gathered(det, c, grp)]);
        const std::vector<double> rel_var = g.rays_rel_var(det, d.cells, site_lx, arrivals, gathered_lx);
        d.gather_rel_var.assign(rel_var.begin(), rel_var.end());
    }
}

void RunLoop::share_annual_estimates() {
    shared_annual_.reset();
    const Traced t = traced();
    update_gather_errors(t.e0);
    // One part per node (its first rank, on all the node's cores): between the ranks of one
    // node, moving the counts and the series costs more than it saves (docs/ANNUAL.md
    // step 7), so one node leaves it to rank 0's write.
    const bool per_rank = opt_.annual_parts_per_rank;
    const int parts = per_rank ? ranks_ : comm_.nodes();
    if (!scene_.annual || parts == 1 || t.photons == 0) return;
    // Each rank's part plus 1 (0: none), known to every rank.
    std::vector<std::uint64_t> part_of(static_cast<std::size_t>(ranks_), 0);
    part_of[static_cast<std::size_t>(comm_.rank())] = static_cast<std::uint64_t>(
        (per_rank ? comm_.rank() : comm_.node_index()) + 1);
    comm_.allreduce_sum(part_of);
    const double s0 = comm_.wtime();
    std::vector<std::optional<AnnualDetectorEstimate>> out(scene_.detectors.size());
    PartAttempt attempt;
    for (std::size_t det = 0; det < scene_.detectors.size(); ++det) {
        if (!annual_grid(scene_.detectors[det])) continue;
        const std::size_t cells = static_cast<std::size_t>(scene_.detectors[det].cells());
        std::vector<AnnualCellRange> ranges;
        for (const std::uint64_t p : part_of)
            ranges.push_back(p == 0 ? AnnualCellRange{} : annual_part_cells(cells, static_cast<int>(p - 1), parts));
        DirectCoefficients own_direct;
        const DirectCoefficients* direct = nullptr;
        const AnnualDarkRates dark = share_annual_inputs(det, ranges, t, own_direct, direct, attempt);
        AnnualGridPart part;
        attempt([&] {
            part = estimate_annual_part(scene_, det, layout_, totals_.span(), t.e0, t.photons, kAnnualReplicates,
                                        ranges[static_cast<std::size_t>(comm_.rank())], dark, direct);
        });
        gather_annual_part(det, ranges, std::move(part), direct, attempt, out[det]);
        if (comm_.is_root() && out[det])
            attempt(
                [&] { annual_gather_year(scene_, det, layout_, totals_.span(), t.e0, t.photons, direct, *out[det]); });
    }
    shared_annual_s_ = comm_.wtime() - s0;
    if (!comm_.is_root()) return;
    if (!attempt.failed) shared_annual_ = std::move(out);
    else
        out_ << "luxtrace: the annual post-processing shared by the ranks failed (" << attempt.error
             << "); rank 0 does it alone\n";
}

AnnualDarkRates RunLoop::share_annual_inputs(std::size_t det, const std::vector<AnnualCellRange>& ranges,
                                             const Traced& t, DirectCoefficients& own_direct,
                                             const DirectCoefficients*& direct, PartAttempt& attempt) {
    const bool root = comm_.is_root(), shadow = scene_.annual->options.shadow_rays();
    const AnnualCellRange mine = ranges[static_cast<std::size_t>(comm_.rank())];
    // The grid's dark rates, from rank 0's whole grid.
    std::vector<double> dark(2, 0.0);
    if (root)
        attempt([&] {
            const AnnualDarkRates d = annual_dark_rates(scene_, det, layout_, totals_.span(), t.e0, t.photons,
                                                        shadow ? &annual_direct_[det] : nullptr);
            dark = {d.total, d.direct};
            dark.insert(dark.end(), d.gather_total.begin(), d.gather_total.end());
        });
    // A gathered grid's factors, per light group, after the two rates.
    if (layout_.gathered(det)) dark.resize(2 + kGatherFactorWords * layout_.groups(), 0.0);
    comm_.broadcast(dark);
    // Each rank's cells' counts: their n and q, their direct counts and their gathered
    // sums, where rank 0 keeps them in totals_.
    auto word_runs = [&](const AnnualCellRange& r) {
        std::vector<std::pair<std::size_t, std::size_t>> w{
            {layout_.detector_cell(det, r.first, 0), layout_.detector_cell(det, r.last, 0)}};
        if (layout_.direct_scores())
            w.emplace_back(layout_.detector_direct(det, r.first, 0), layout_.detector_direct(det, r.last, 0));
        if (layout_.gathered(det))  // column by column (tally.hpp)
            for (std::size_t col = 0; col < layout_.detector_columns(); ++col)
                w.emplace_back(layout_.detector_gathered(det, r.first, col),
                               layout_.detector_gathered(det, r.last, col));
        return w;
    };
    const std::span<std::uint64_t> totals = totals_.span();
    std::vector<std::size_t> counts;
    std::vector<std::uint64_t> send, recv;
    for (const AnnualCellRange& r : ranges) {
        counts.push_back(0);
        for (const auto& [b, e] : word_runs(r)) {
            counts.back() += e - b;
            if (root)
                send.insert(send.end(), totals.begin() + static_cast<std::ptrdiff_t>(b),
                            totals.begin() + static_cast<std::ptrdiff_t>(e));
        }
    }
    comm_.scatter_from_root<std::uint64_t>(send, counts, recv);
    if (!root) {
        std::size_t at = 0;
        for (const auto& [b, e] : word_runs(mine)) {
            std::copy_n(recv.begin() + static_cast<std::ptrdiff_t>(at), e - b,
                        totals.begin() + static_cast<std::ptrdiff_t>(b));
            at += e - b;
        }
    }
    // Each rank's cells' direct coefficients.
    if (shadow) {
        own_direct.resize(root ? 0 : mine.last - mine.first, scene_.annual->sky->sky_entries(),
                          scene_.annual->sky->suns().size(), mine.first);
        if (layout_.gathered(det)) {
            own_direct.gather_unit_lx_per_lm = surfaces_.gather().unit_lx_per_lm();
            own_direct.gather_rel_var.assign(own_direct.cells, 0.0F);  // filled from rank 0's below
        }
        const DirectCoefficients& all = root ? annual_direct_[det] : own_direct;
        std::vector<float> dsend, drecv;
        std::vector<std::size_t> dcounts;
        for (const AnnualCellRange& r : ranges) {
            dcounts.push_back(all.packed_words(r.last - r.first));
            if (root) all.pack_cells(r.first, r.last, dsend);
        }
        comm_.scatter_from_root<float>(dsend, dcounts, drecv);
        if (!root) own_direct.unpack_cells(drecv, mine.first, mine.last);
        direct = root ? &annual_direct_[det] : &own_direct;
    }
    return {dark[0], dark[1], std::vector<double>(dark.begin() + 2, dark.end())};
}

void RunLoop::gather_annual_part(std::size_t det, const std::vector<AnnualCellRange>& ranges, AnnualGridPart part,
                                 const DirectCoefficients* direct, PartAttempt& attempt,
                                 std::optional<AnnualDetectorEstimate>& out) {
    // A status word and the metric sums, and the four series, each rank's in rank order.
    const std::size_t hours = scene_.annual->sky->hours().size(), rank = static_cast<std::size_t>(comm_.rank());
    std::vector<std::size_t> word_counts, series_counts;
    for (const AnnualCellRange& r : ranges) {
        word_counts.push_back(1 + AnnualMetricDraws::word_count(hours, r.last - r.first, kAnnualReplicates));
        series_counts.push_back(4 * hours * (r.last - r.first));
    }
    std::vector<std::uint64_t> words{attempt.failed ? 1u : 0u};
    std::vector<double> series;
    if (attempt.failed) {
        words.resize(word_counts[rank], 0);
        series.assign(series_counts[rank], 0.0);
    } else {
        words.insert(words.end(), part.metric_words.begin(), part.metric_words.end());
        for (const std::vector<double>* x :
             {&part.value.total_lx, &part.value.direct_lx, &part.sigma.total_lx, &part.sigma.direct_lx})
            series.insert(series.end(), x->begin(), x->end());
    }
    part = {};
    std::vector<std::uint64_t> all_words;
    std::vector<double> all_series;
    comm_.gather_to_root<std::uint64_t>(words, word_counts, all_words);
    comm_.gather_to_root<double>(series, series_counts, all_series);
    if (!comm_.is_root()) return;
    attempt([&] {
        for (std::size_t w = 0, r = 0; r < ranges.size(); w += word_counts[r++])
            if (all_words[w] != 0) throw std::runtime_error("rank " + std::to_string(r) + "'s part failed");
        const AnnualSeriesSink sink = series_sink();
        AnnualPartsMerge merge(scene_, det, kAnnualReplicates, direct, &sink);
        std::size_t w = 0, x = 0;
        for (std::size_t r = 0; r < ranges.size(); w += word_counts[r++]) {
            AnnualGridPart p;
            p.cells = ranges[r];
            p.metric_words.assign(all_words.begin() + static_cast<std::ptrdiff_t>(w + 1),
                                  all_words.begin() + static_cast<std::ptrdiff_t>(w + word_counts[r]));
            const std::size_t n = ranges[r].last - ranges[r].first, len = hours * n;
            for (AnnualSeries* a : {&p.value, &p.sigma}) {
                a->hours = hours;
                a->sensors = n;
            }
            for (std::vector<double>* v :
                 {&p.value.total_lx, &p.value.direct_lx, &p.sigma.total_lx, &p.sigma.direct_lx}) {
                v->assign(all_series.begin() + static_cast<std::ptrdiff_t>(x),
                          all_series.begin() + static_cast<std::ptrdiff_t>(x + len));
                x += len;
            }
            merge.add(p);
        }
        all_series = {};
        out = merge.finish();
    });
}

void RunLoop::reduce() {
    const double r0 = comm_.wtime();
    wait_s_ = 0.0;
    PendingReduce pending = start_reduce();
    timed_wait([&] {
        while (!pending.test()) std::this_thread::sleep_for(std::chrono::microseconds(500));
    });
    finish_reduce();
    // The work is what the main thread did itself; the waits for other ranks (the blocking
    // collectives, the messages in flight) are apart: they take no core from tracing.
    work_s_ = comm_.wtime() - r0 - wait_s_;
    reduce_wait_total_s_ += wait_s_;
    reduce_work_total_s_ += work_s_;
}

Decision RunLoop::decide() {
    if (!comm_.is_root()) return {};
    const ReductionMessage& m = summed_header_;
    if (m.flags.input_fault > 0 || m.flags.internal_fault > 0) {
        const Decision d = Decision::fault(m.flags.internal_fault > 0);
        summary_.stop_reason = d.reason;
        return d;
    }
    ReductionInput in;
    in.tallies = totals_.span();
    in.globals = globals_;
    in.photons = photons_;
    in.elapsed_s = comm_.wtime() - t0_;
    in.tracing_start_s = trace0_ - t0_;
    in.all_ranks_idle = m.flags.idle == static_cast<std::uint64_t>(ranks_);
    in.signalled = m.flags.signalled > 0;
    in.stall_s = stall_s_;
    in.work_s = work_s_;
    in.write_s = write_s_;
    // An annual target's errors need the gather's own (its words over every cell and light
    // group: not read after each reduction for nothing).
    if (std::any_of(run_.targets.begin(), run_.targets.end(), [](const Target& t) { return !t.annual_metric.empty(); }))
        update_gather_errors(traced().e0);
    in.annual_direct = &annual_direct_;
    Decision d;
    try {
        d = WriteSteps("run", opt_.inject_fault).run("decide", [&] { return control_->after_reduction(in); });
    } catch (const std::exception& e) {
        // Rank 0's own fault: the tallies are whole, every rank stops and keeps them (write).
        decide_error_ = e.what();
        d = Decision::decision_fault();
        summary_.stop_reason = d.reason;
        decided_elapsed_s_ = in.elapsed_s;
        return d;
    }
    if (show_) out_ << (tty_ ? "\r" : "") << control_->progress_line() << (tty_ ? "\033[K" : "\n") << std::flush;
    summary_.stop_reason = d.reason;
    decided_elapsed_s_ = in.elapsed_s;
    return d;
}

void RunLoop::checkpoint(const Decision& d) {
    // A periodic checkpoint comes from this exact reduction; a final one (exit 3) from the
    // final reduction, which holds more photons.
    if (!d.checkpoint || d.stop) return;
    const double w0 = comm_.wtime();
    gather_map();
    if (comm_.is_root()) {
        // A failed periodic checkpoint leaves the previous one intact: warn, go on.
        const std::string before = latest_checkpoint_note();
        if (const WriteOutcome w = keep_checkpoint(decided_elapsed_s_, "checkpoint", false); !w.ok())
            std::cerr << "luxtrace: warning: checkpoint not written: " << w.error << "; " << before
                      << "; the run goes on\n"
                      << std::flush;
        write_s_ = comm_.wtime() - w0;
    }
}

Decision RunLoop::broadcast(const Decision& decision) {
    std::vector<double> words = comm_.is_root() ? decision.encode() : std::vector<double>(Decision::kWords, 0.0);
    comm_.broadcast(words);
    Decision d = Decision::decode(words);
    if (comm_.is_root()) d.reason = decision.reason;
    period_s_ = d.next_period_s;
    return d;
}

RunLoop::Traced RunLoop::traced() const {
    Traced t;
    t.done = plan_.done_ranges(summed_header_.progress);
    t.photons = count_photons(t.done);
    t.e0 = t.photons > 0 ? scene_.lights.total_flux_lm() / static_cast<double>(t.photons) : 0.0;
    return t;
}

AnnualSeriesFile& RunLoop::series_file() {
    if (!series_file_) {
        std::vector<std::size_t> cells;
        for (const Detector& d : scene_.detectors)
            cells.push_back(annual_grid(d) ? static_cast<std::size_t>(d.cells()) : 0);
        std::vector<std::uint8_t> daylit;
        for (const AnnualHour& h : scene_.annual->sky->hours()) daylit.push_back(h.daylit ? 1 : 0);
        series_file_ = std::make_unique<AnnualSeriesFile>(run_.output, cells, daylit, kAnnualBlockCells);
    }
    return *series_file_;
}

AnnualSeriesSink RunLoop::series_sink() {
    AnnualSeriesFile& f = series_file();
    return [&f](std::size_t det, std::size_t first, const AnnualSeries& value, const AnnualSeries& sigma) {
        f.write(det, first, value, sigma);
    };
}

AnnualSeriesSource RunLoop::series_source() {
    AnnualSeriesFile& f = series_file();
    AnnualSeriesSource s;
    s.read_hours = [&f](std::size_t det, AnnualSeriesKind kind, std::size_t h0, std::size_t h1, std::span<float> out) {
        f.read_hours(det, kind, h0, h1, out);
    };
    s.read_cells = [&f](std::size_t det, AnnualSeriesKind kind, std::size_t first, std::size_t count,
                        std::span<float> out) { f.read_cells(det, kind, first, count, out); };
    return s;
}

RunInfo RunLoop::final_info(const Traced& t, double elapsed_s, const std::string& reason) const {
    RunInfo i = info_;
    i.photons = t.photons;
    i.flux_per_photon_lm = t.e0;
    i.elapsed_s = restored_.elapsed_s + elapsed_s;
    i.stop_reason = reason;
    control_->fill_run_info(i);
    return i;
}

CheckpointData RunLoop::checkpoint_data(const std::vector<PhotonRange>& done) const {
    CheckpointData ck;
    const std::span<const std::uint64_t> tallies = totals_.span();
    ck.tallies.assign(tallies.begin(), tallies.end());
    for (const PhotonRange& r : done) ck.done.insert(ck.done.end(), {r.begin, r.end});
    ck.budget = run_.photons;
    return ck;
}

void RunLoop::write_file(const std::string& path, double elapsed_s, const std::string& reason, bool as_checkpoint) {
    const WriteSteps steps(as_checkpoint ? "checkpoint" : "result", opt_.inject_fault);
    const Traced t = traced();
    const std::uint64_t n = t.photons;
    const double e0 = t.e0;
    const std::span<const std::uint64_t> tallies = totals_.span();
    ResultEstimates est = steps.run("estimates", [&] { return estimate_result(scene_, layout_, tallies, e0, n); });
    // The annual metrics' errors take a few dozen replicate years: the final result only.
    if (scene_.annual && !as_checkpoint && shared_annual_) {
        // Made by every rank before the write (share_annual_estimates).
        est.annual = steps.run("annual", [&] { return std::move(*shared_annual_); });
        steps.add_seconds("annual", shared_annual_s_);
        shared_annual_.reset();
        shared_annual_used_ = true;
    } else if (scene_.annual)
        est.annual = steps.run("annual", [&] {
            update_gather_errors(e0);
            const AnnualSeriesSink sink = series_sink();
            return estimate_annual(scene_, layout_, tallies, e0, n, as_checkpoint ? 0 : kAnnualReplicates,
                                   annual_direct_, &sink);
        });
    if (scene_.annual) est.annual_series = series_source();
    const RunInfo i = final_info(t, elapsed_s, reason);
    const CheckpointData ck = as_checkpoint ? checkpoint_data(t.done) : CheckpointData{};
    const std::vector<char> image = steps.run("image", [&] {
        return result_image(path, scene_, layout_, tallies, i, est, control_->history(), as_checkpoint ? &ck : nullptr);
    });
    steps.run("rename", [&] { write_file_atomically(path, image, steps.before_rename(path)); });
    if (!as_checkpoint) result_on_disk_ = true;
    if (!as_checkpoint && scene_.annual && scene_.annual->options.write_ladybug) {
        const std::filesystem::path folder = ladybug_folder_for(scene_, path);
        try {
            steps.run("ladybug", [&] { write_annual_ladybug(folder, scene_, est.annual, est.annual_series); });
        } catch (const IoError& e) {
            throw IoError("the result " + path + " was written, the Ladybug results folder " + folder.string() +
                          " was not: " + e.what());
        } catch (const WriteStepError& e) {
            throw WriteStepError("the result " + path + " was written, the Ladybug results folder " + folder.string() +
                                 " was not: " + e.what());
        }
    }
    // Each points detector's table beside the final result (not beside checkpoints). The
    // tables repeat numbers the result holds: one that cannot be written only warns.
    if (!as_checkpoint) {
        std::vector<std::string> failures;
        summary_.sensor_tables.clear();
        try {
            for (const std::filesystem::path& table : write_sensor_tables(path, scene_, est, n, failures))
                summary_.sensor_tables.push_back(table.string());
        } catch (const std::exception& e) {
            failures.push_back(e.what());
        }
        for (const std::string& f : failures)
            std::cerr << "luxtrace: warning: sensor table not written: " << f << "; the result " << path
                      << " holds its numbers (Python: luxtrace.sensor_table)\n"
                      << std::flush;
    }
    if (!as_checkpoint) summary_.result_steps_s = steps.seconds();
    summary_.photons = n;
    summary_.global = est.global;
    summary_.detectors = std::move(est.detectors);
}

void RunLoop::write_tally_checkpoint(const std::string& path, double elapsed_s, const std::string& reason) {
    const WriteSteps steps("tallies", opt_.inject_fault);
    const Traced t = traced();
    const RunInfo i = final_info(t, elapsed_s, reason);
    const CheckpointData ck = checkpoint_data(t.done);
    const std::vector<char> image = steps.run("image", [&] {
        return tally_checkpoint_image(path, scene_, layout_, i, control_->history(), ck);
    });
    steps.run("rename", [&] { write_file_atomically(path, image, steps.before_rename(path)); });
    summary_.photons = t.photons;
}

WriteOutcome RunLoop::attempt(const std::function<void()>& write) {
    try {
        write();
        return {};
    } catch (const IoError& e) {
        return {e.what(), false};
    } catch (const WriteStepError& e) {
        return {e.what(), true};
    } catch (const std::exception& e) {
        return {std::string("internal error: ") + e.what(), true};
    } catch (...) {
        return {"internal error: an unknown exception", true};
    }
}

WriteOutcome RunLoop::attempt_write(const std::string& path, double elapsed_s, const std::string& reason,
                                    bool as_checkpoint) {
    return attempt([&] { write_file(path, elapsed_s, reason, as_checkpoint); });
}

WriteOutcome RunLoop::keep_checkpoint(double elapsed_s, const std::string& reason, bool beside_result) {
    WriteOutcome full = attempt_write(checkpoint_path_, elapsed_s, reason, true);
    std::string written = full.ok() ? checkpoint_path_ : std::string{};
    // The tallies alone, where the checkpoint goes and then beside the result: no
    // estimates, no maps, the fewest steps that can fail.
    WriteOutcome tallies;
    std::vector<std::string> places{checkpoint_path_};
    if (const std::string beside = run_.output + ".checkpoint.h5"; beside_result && beside != checkpoint_path_)
        places.push_back(beside);
    for (const std::string& path : places) {
        if (!written.empty()) break;
        tallies = attempt([&] { write_tally_checkpoint(path, elapsed_s, reason); });
        if (tallies.ok()) written = path;
    }
    if (written.empty()) {
        WriteOutcome out = full;
        if (tallies.error != full.error) out.error += "; nor the tallies alone: " + tallies.error;
        out.internal = full.internal && tallies.internal;
        return out;
    }
    latest_checkpoint_ = written;
    latest_checkpoint_photons_ = summary_.photons;
    if (!full.ok())
        std::cerr << "luxtrace: warning: the checkpoint " << checkpoint_path_ << " could not be made whole ("
                  << full.error << "); the run's tallies alone are kept in " << written << "\n"
                  << std::flush;
    return {};
}

std::string RunLoop::latest_checkpoint_note() const {
    if (latest_checkpoint_.empty()) return "no checkpoint of this run was written before";
    return "the latest checkpoint " + latest_checkpoint_ + " (" + std::to_string(latest_checkpoint_photons_) +
           " photons) is kept";
}

std::string RunLoop::tallies_kept_note(const std::string& then) const {
    const std::string scene = opt_.scene_args.empty() ? scene_.file.string() : opt_.scene_args;
    return "luxtrace: the run's tallies (" + std::to_string(summary_.photons) +
           " photons) are kept in the checkpoint " + latest_checkpoint_ + "; " + then + ": luxtrace run " + scene +
           " --restart " + latest_checkpoint_ + " --output " + run_.output;
}

void RunLoop::explain_failed_writes(const WriteOutcome& result, const WriteOutcome& checkpoint) {
    // A run stopped early continues from its checkpoint; a finished one only writes.
    const std::string then = summary_.exit_code == kExitStoppedEarly ? "continue with"
                                                                     : "write the result from it with";
    summary_.exit_code = result.internal || checkpoint.internal ? kExitInternal : kExitWriteFailed;
    summary_.failed = true;
    summary_.write_failed = true;
    if (!result.ok()) {
        // A failure after the result's rename (the Ladybug folder) says so itself.
        summary_.error =
            (result_on_disk_ ? result.error : "the result " + run_.output + " was not written: " + result.error) + "\n";
        if (checkpoint.ok()) summary_.error += tallies_kept_note(then);
        else
            summary_.error += "luxtrace: the checkpoint was not written either: " + checkpoint.error +
                              "\nluxtrace: " + latest_checkpoint_note();
    } else {
        summary_.error = "the result " + run_.output +
                         " was written, but the checkpoint to continue from was not: " + checkpoint.error +
                         "\nluxtrace: " + latest_checkpoint_note();
    }
}

RunSummary RunLoop::write(const Decision& decision) {
    if (tty_) out_ << '\n';
    // The final exact reduction: the threads finish their chunks and flush.
    pool_->stop();
    summary_.tracing_s = comm_.allreduce_max(pool_->tracing_s());
    summary_.tracing_busy = info_.tracing_busy = 1.0 - comm_.allreduce_max(1.0 - pool_->busy_fraction());
    // A tracing fault (a rank's thread failed: its counts cannot be trusted) writes nothing;
    // a fault of rank 0's decision keeps the tallies (below).
    if (decision.exit_code == kExitBadInput || (decision.exit_code == kExitInternal && !decision.checkpoint)) {
        summary_.exit_code = decision.exit_code;
        summary_.failed = true;
        if (pool_->failed()) summary_.error = describe(pool_->error());
        return summary_;
    }
    if (!decision.result_is_snapshot) {
        encode_snapshot(false, false);
        start_reduce().wait();
        finish_reduce();
    }
    const double g0 = comm_.wtime();
    gather_map();
    info_.gather_s = comm_.allreduce_max(comm_.wtime() - g0);
    if (decision.exit_code != kExitInternal) share_annual_estimates();
    const double elapsed = comm_.allreduce_max(comm_.wtime() - t0_);
    info_.load_s = comm_.allreduce_max(opt_.load_s);
    info_.bvh_build_s = comm_.allreduce_max(embree_.build_s());
    info_.reductions = reductions_;
    info_.reduction_stall_s = comm_.allreduce_max(stall_total_s_);
    info_.reduction_wait_s = comm_.allreduce_max(reduce_wait_total_s_);
    info_.reduction_work_s = comm_.allreduce_max(reduce_work_total_s_);
    summary_.elapsed_s = restored_.elapsed_s + elapsed;
    summary_.exit_code = decision.exit_code;
    std::vector<double> final_code{static_cast<double>(summary_.exit_code)};
    if (comm_.is_root()) {
        // Each intersection ends in an arrival on a triangle or in an escape.
        summary_.rays = totals_[layout_.counter(TallyLayout::kEscaped)];
        for (std::size_t i = 0; i < layout_.sides(); ++i)
            for (std::size_t c = 0; c < layout_.map_columns(); ++c)
                summary_.rays += totals_[layout_.map_slot(i, c, TallyLayout::kCountOdd)] +
                                 totals_[layout_.map_slot(i, c, TallyLayout::kCountEven)];
        if (decision.exit_code == kExitInternal) keep_after_decision_fault(elapsed);
        else write_result_and_checkpoint(decision, elapsed);
        final_code[0] = summary_.exit_code;
    }
    // Every rank ends with rank 0's verdict on the writes.
    comm_.broadcast(final_code);
    summary_.exit_code = static_cast<int>(final_code[0]);
    summary_.failed = summary_.failed || (summary_.exit_code != kExitOk && summary_.exit_code != kExitStoppedEarly);
    return summary_;
}

void RunLoop::keep_after_decision_fault(double elapsed) {
    const WriteOutcome ck = keep_checkpoint(elapsed, summary_.stop_reason, true);
    summary_.exit_code = kExitInternal;
    summary_.failed = summary_.write_failed = true;
    summary_.error = decide_error_ + "\n";
    if (ck.ok()) {
        summary_.checkpoint = latest_checkpoint_;
        summary_.error += tallies_kept_note("continue with");
    } else
        summary_.error += "luxtrace: the checkpoint was not written: " + ck.error +
                          "\nluxtrace: " + latest_checkpoint_note();
}

void RunLoop::write_result_and_checkpoint(const Decision& decision, double elapsed) {
    const double w0 = comm_.wtime();
    const WriteOutcome result = attempt_write(run_.output, elapsed, summary_.stop_reason, false);
    // With the annual post-processing every rank's, its time before the write counts too.
    summary_.result_write_s = comm_.wtime() - w0 + (shared_annual_used_ ? shared_annual_s_ : 0.0);
    // A result that cannot be written: keep the tallies in a checkpoint instead.
    const bool want_checkpoint = summary_.exit_code == kExitStoppedEarly || decision.checkpoint || !result.ok();
    WriteOutcome checkpoint;
    if (want_checkpoint) checkpoint = keep_checkpoint(elapsed, summary_.stop_reason, true);
    if (want_checkpoint && checkpoint.ok()) summary_.checkpoint = latest_checkpoint_;
    if (!result.ok() || !checkpoint.ok()) explain_failed_writes(result, checkpoint);
}

}  // namespace luxtrace
