#include "preview/refiner.h"

#include "trace/sampling.h"

#include <algorithm>
#include <chrono>
#include <numeric>

namespace glint {

RefineJob::RefineJob(std::shared_ptr<const World> world, std::shared_ptr<const IdImage> ids,
                     Resolve resolve, bool compare_with_ray)
    : world_(std::move(world)), ids_(std::move(ids)), resolve_(resolve),
      compare_with_ray_(compare_with_ray && ids_) {
    const int width = world_->camera().width(), height = world_->camera().height();
    final_ = normals_ = difference_ = reflections_ = Image(width, height);
    order_.resize(static_cast<std::size_t>(glint::tile_count(width, height)));
    std::iota(order_.begin(), order_.end(), 0);
    const auto distance = [&](int index) {
        const TileRect r = tile(index);
        const double dx = (r.x0 + r.x1) * 0.5 - width * 0.5,
                     dy = (r.y0 + r.y1) * 0.5 - height * 0.5;
        return dx * dx + dy * dy;
    };
    std::stable_sort(order_.begin(), order_.end(),
                     [&](int a, int b) { return distance(a) < distance(b); });
    done_ = std::make_unique<std::atomic<int>[]>(order_.size());
    const RenderSettings& settings = world_->settings();
    if (settings.samples > 1) {
        passes_ = 2;
        if (settings.antialias == Antialias::adaptive) {
            passes_ = 3; // the rule's spreading (trace/sampling.h, rule 4), after the grids
            path_keys_.assign(static_cast<std::size_t>(width) * height, 0);
        }
    }
}

const Image& RefineJob::traced(View view, int passes) const {
    switch (view) {
    case View::normals:
        return normals_;
    case View::difference:
        return difference_;
    case View::reflections:
        return reflections_;
    default:
        if (passes > 2 && passes_ > 2) return spread_;
        return passes > 1 && passes_ > 1 ? sampled_ : final_;
    }
}

TileRect RefineJob::tile(int index) const {
    return tile_rect(width(), height(), index);
}

void RefineJob::work(const std::atomic<bool>& cancel) {
    const int tiles = tile_count(), tile_passes = std::min(passes_, 2);
    for (int k = next_++; k < tile_passes * tiles && !cancel.load(std::memory_order_relaxed);
         k = next_++) {
        const int index = order_[static_cast<std::size_t>(k % tiles)];
        if (k < tiles) {
            trace_tile(tile(index));
        } else {
            if (!wait_for_first_pass(cancel)) return;
            refine_tile(tile(index));
        }
        done_[index].fetch_add(1, std::memory_order_acq_rel);
        int done = tiles_done_.fetch_add(1, std::memory_order_acq_rel) + 1;
        if (done == tiles && passes_ > 1) plan_refinement();
        if (done == 2 * tiles && passes_ > 2) {
            spread(cancel); // by this worker alone, then every tile is done a third time
            for (int t = 0; t < tiles; ++t) done_[t].fetch_add(1, std::memory_order_acq_rel);
            done = tiles_done_.fetch_add(tiles, std::memory_order_acq_rel) + tiles;
        }
        if (done == passes_ * tiles) {
            const std::lock_guard lock(totals_mutex_);
            seconds_ = watch_.seconds();
        }
    }
}

void RefineJob::plan_refinement() {
    const RenderSettings& settings = world_->settings();
    if (settings.antialias == Antialias::adaptive)
        refine_ = adaptive_refinement(final_, path_keys_, nullptr, settings.samples,
                                      settings.aa_threshold);
    else
        refine_.assign(static_cast<std::size_t>(width()) * height(), 1);
    sampled_ = final_;
    {
        const std::lock_guard lock(totals_mutex_);
        refined_ = static_cast<std::uint64_t>(std::count(refine_.begin(), refine_.end(), 1));
    }
    planned_.store(true, std::memory_order_release);
}

bool RefineJob::wait_for_first_pass(const std::atomic<bool>& cancel) {
    while (!planned_.load(std::memory_order_acquire)) {
        if (cancel.load(std::memory_order_relaxed)) return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(1)); // at most one tile's wait
    }
    return true;
}

// The second pass: the planned pixels' N×N grids, by camera ray (exact resolve would give the
// same hits; the preview keeps one item buffer, of the pixel centres).
void RefineJob::refine_tile(const TileRect& rect) {
    std::vector<Hit> hits;
    RayCounts counts;
    for (int y = rect.y0; y < rect.y1; ++y)
        for (int x = rect.x0; x < rect.x1; ++x)
            if (refine_[static_cast<std::size_t>(y) * width() + x])
                counts += grid_into(sampled_, x, y, hits);
    const std::lock_guard lock(totals_mutex_);
    rays_ += counts;
}

// Rule 4 of the adaptive rule, round by round as trace_frame applies it, into a copy of the
// second pass's image.
void RefineJob::spread(const std::atomic<bool>& cancel) {
    spread_ = sampled_;
    std::vector<Hit> hits;
    RayCounts counts;
    const std::size_t refined =
        spread_refinement(final_, spread_, refine_, world_->settings().aa_threshold,
                          [&](const std::vector<std::uint8_t>& next) {
                              for (std::size_t i = 0; i < next.size(); ++i)
                                  if (next[i])
                                      counts += grid_into(spread_, static_cast<int>(i % width()),
                                                          static_cast<int>(i / width()), hits);
                              return !cancel.load(std::memory_order_relaxed);
                          });
    const std::lock_guard lock(totals_mutex_);
    rays_ += counts;
    refined_ += refined;
}

// Pixel (x, y)'s grid mean into `image`, its samples cast as rays; returns their ray counts.
RayCounts RefineJob::grid_into(Image& image, int x, int y, std::vector<Hit>& hits) const {
    PrimaryStats unused; // counted only when resolving ids
    const GridPixel pixel = trace_grid(*world_, {}, x, y, hits, unused);
    store_colour(pixel.mean, image.pixel(x, y));
    return pixel.rays;
}

std::uint64_t RefineJob::refined_pixels() const {
    const std::lock_guard lock(totals_mutex_);
    return refined_;
}

// Each pixel through trace/pixel.h's path, as `glint render` traces it; the other views show
// what that path computed, and only the difference view casts a ray of its own.
void RefineJob::trace_tile(const TileRect& rect) {
    const World& world = *world_;
    const PrimarySource source{ids_.get(), resolve_};
    const int max_depth = world.settings().max_depth;
    RayCounts counts;
    PrimaryStats stats;
    std::uint64_t differing = 0;
    for (int y = rect.y0; y < rect.y1; ++y) {
        for (int x = rect.x0; x < rect.x1; ++x) {
            const PixelSample sample = trace_pixel(world, source, x, y, stats);
            const Hit& hit = sample.hit;
            std::uint8_t* p = final_.pixel(x, y);
            store_colour(sample.colour, p);
            const Rgb depth = reflection_colour(sample.depth, max_depth);
            std::copy(depth.begin(), depth.end(), reflections_.pixel(x, y));
            const Rgb normal = hit.found() ? normal_colour(glm::vec3(sample.normal)) : Rgb{0, 0, 0};
            std::copy(normal.begin(), normal.end(), normals_.pixel(x, y));
            const Hit by_ray = compare_with_ray_ ? world.intersect(world.camera().ray(x, y)) : hit;
            const bool differs =
                by_ray.found() != hit.found() || (hit.found() && by_ray.object != hit.object);
            differing += differs;
            const Rgb diff = difference_colour(p, differs);
            std::copy(diff.begin(), diff.end(), difference_.pixel(x, y));
            counts += sample.rays;
            if (!path_keys_.empty())
                path_keys_[static_cast<std::size_t>(y) * width() + x] = sample.path_key;
        }
    }
    const std::lock_guard lock(totals_mutex_);
    rays_ += counts;
    stats_ += stats;
    differing_ += differing;
}

RayCounts RefineJob::rays() const {
    const std::lock_guard lock(totals_mutex_);
    return rays_;
}

PrimaryStats RefineJob::primary_stats() const {
    const std::lock_guard lock(totals_mutex_);
    return stats_;
}

std::uint64_t RefineJob::differing_pixels() const {
    const std::lock_guard lock(totals_mutex_);
    return differing_;
}

double RefineJob::seconds() const {
    const std::lock_guard lock(totals_mutex_);
    return seconds_;
}

Refiner::Refiner(int threads)
    : threads_(threads > 0 ? threads
                           : std::max(1, static_cast<int>(std::thread::hardware_concurrency()))) {}

void Refiner::start(std::shared_ptr<RefineJob> job) {
    stop();
    job_ = std::move(job);
    cancel_ = false;
    for (int i = 0; i < threads_; ++i)
        workers_.emplace_back([this, job = job_] { job->work(cancel_); });
}

void Refiner::stop() {
    cancel_ = true;
    for (std::thread& worker : workers_) worker.join();
    workers_.clear();
    job_.reset();
}

} // namespace glint
