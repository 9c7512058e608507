#include "preview/refiner.h"

#include <algorithm>
#include <numeric>

namespace glint {

RefineJob::RefineJob(std::shared_ptr<const World> world, std::shared_ptr<const IdImage> ids,
                     Resolve resolve, bool compare_with_ray)
    : world_(std::move(world)), ids_(std::move(ids)), resolve_(resolve),
      compare_with_ray_(compare_with_ray && ids_) {
    const int width = world_->camera().width(), height = world_->camera().height();
    final_ = normals_ = difference_ = reflections_ = Image(width, height);
    tiles_x_ = (width + kTileSize - 1) / kTileSize;
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
    done_ = std::make_unique<std::atomic<bool>[]>(order_.size());
}

const Image& RefineJob::traced(View view) const {
    switch (view) {
    case View::normals:
        return normals_;
    case View::difference:
        return difference_;
    case View::reflections:
        return reflections_;
    default:
        return final_;
    }
}

TileRect RefineJob::tile(int index) const {
    const int x0 = (index % tiles_x_) * kTileSize, y0 = (index / tiles_x_) * kTileSize;
    return {x0, y0, std::min(x0 + kTileSize, width()), std::min(y0 + kTileSize, height())};
}

void RefineJob::work(const std::atomic<bool>& cancel) {
    for (int k = next_++; k < tile_count() && !cancel.load(std::memory_order_relaxed);
         k = next_++) {
        trace_tile(tile(order_[static_cast<std::size_t>(k)]));
        done_[order_[static_cast<std::size_t>(k)]].store(true, std::memory_order_release);
        if (tiles_done_.fetch_add(1, std::memory_order_acq_rel) + 1 == tile_count()) {
            const std::lock_guard lock(totals_mutex_);
            seconds_ = watch_.seconds();
        }
    }
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
