#include "preview/refiner.h"

#include "trace/render.h"

#include <algorithm>
#include <numeric>

namespace glint {

// The preview's tiles: each pass's tiles on `threads` worker threads started for the pass, taken
// in the job's order (centre first), each shown as soon as it is traced; no tile is started once
// `cancel` is set.
class RefineJob::PreviewSchedule final : public TileSchedule {
  public:
    PreviewSchedule(RefineJob& job, const std::atomic<bool>& cancel, int threads)
        : job_(job), cancel_(cancel), threads_(threads) {}

    bool run(FramePass pass, const RenderResult& result, const TileWork& work) override {
        std::atomic<std::size_t> next{0};
        const auto worker = [&] {
            for (std::size_t k = next++; k < job_.order_.size(); k = next++) {
                if (cancel_.load(std::memory_order_relaxed)) return;
                const int index = job_.order_[k];
                const RayCounts rays = work(job_.tile(index));
                job_.show_tile(pass, index, result, rays);
            }
        };
        std::vector<std::thread> workers;
        for (int t = 1; t < threads_; ++t) workers.emplace_back(worker);
        worker();
        for (std::thread& w : workers) w.join();
        return !cancel_.load(std::memory_order_relaxed);
    }
    void finish(FramePass pass, RenderResult& result) override {
        job_.pass_done(pass, result);
    }

  private:
    RefineJob& job_;
    const std::atomic<bool>& cancel_;
    int threads_;
};

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
    if (settings.samples > 1) passes_ = settings.antialias == Antialias::adaptive ? 3 : 2;
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

Image& RefineJob::image_of(FramePass pass) {
    switch (pass) {
    case FramePass::centres:
        return final_;
    case FramePass::grids:
        return sampled_;
    case FramePass::spread:
        break;
    }
    return spread_;
}

void RefineJob::run(const std::atomic<bool>& cancel, int threads) {
    PreviewSchedule schedule(*this, cancel, std::max(1, threads));
    PrimaryStats stats;
    PhaseTimes unused;
    FrameRequest request;
    request.centres_first = true; // a first look before the grids
    request.observer = this;
    const RenderResult result =
        run_frame(*world_, {ids_.get(), resolve_}, stats, schedule, unused, request);
    if (cancel.load(std::memory_order_relaxed)) return;
    refined_map_ = result.refined;
    {
        const std::lock_guard lock(totals_mutex_);
        stats_ = stats;
        if (!result.refined.empty())
            refined_ = static_cast<std::uint64_t>(
                std::count(result.refined.begin(), result.refined.end(), 1));
        seconds_ = watch_.seconds();
    }
    if (passes_ > 2) { // the spreading's rounds are shown together, once they are done
        for (int t = 0; t < tile_count(); ++t) done_[t].fetch_add(1, std::memory_order_acq_rel);
        tiles_done_.fetch_add(tile_count(), std::memory_order_acq_rel);
    }
    complete_.store(true, std::memory_order_release);
}

void RefineJob::pixel(int x, int y, const Ray& ray, const PixelSample& sample) {
    const World& world = *world_;
    const Hit& hit = sample.hit;
    const Rgb depth = reflection_colour(sample.depth, world.settings().max_depth);
    std::copy(depth.begin(), depth.end(), reflections_.pixel(x, y));
    const Rgb normal = hit.found() ? normal_colour(glm::vec3(sample.normal)) : Rgb{0, 0, 0};
    std::copy(normal.begin(), normal.end(), normals_.pixel(x, y));
    const Hit by_ray = compare_with_ray_ ? world.intersect(ray) : hit;
    const bool differs =
        by_ray.found() != hit.found() || (hit.found() && by_ray.object != hit.object);
    if (differs) differing_.fetch_add(1, std::memory_order_relaxed);
    std::uint8_t shown[3];
    store_colour(sample.colour, shown);
    const Rgb diff = difference_colour(shown, differs);
    std::copy(diff.begin(), diff.end(), difference_.pixel(x, y));
}

void RefineJob::show_tile(FramePass pass, int index, const RenderResult& result,
                          const RayCounts& rays) {
    Image& image = image_of(pass);
    const TileRect r = tile(index);
    const FloatImage& display = result.display();
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x) {
            const float* c = display.pixel(static_cast<std::size_t>(y) * width() + x);
            std::uint8_t* p = image.pixel(x, y);
            for (int k = 0; k < 3; ++k) p[k] = to_byte(c[k]);
        }
    {
        const std::lock_guard lock(totals_mutex_);
        rays_ += rays;
    }
    if (pass == FramePass::spread) return; // shown with the last round (run)
    done_[index].fetch_add(1, std::memory_order_acq_rel);
    tiles_done_.fetch_add(1, std::memory_order_acq_rel);
}

void RefineJob::pass_done(FramePass pass, const RenderResult& result) {
    if (pass == FramePass::centres && passes_ > 1) {
        sampled_ = final_;
        if (passes_ == 2) { // uniform: every pixel's grid
            const std::lock_guard lock(totals_mutex_);
            refined_ = static_cast<std::uint64_t>(width()) * height();
        }
    }
    if (pass == FramePass::grids && passes_ > 2) {
        spread_ = sampled_;
        const std::lock_guard lock(totals_mutex_); // adaptive: the rule's pixels, before spreading
        refined_ = static_cast<std::uint64_t>(
            std::count(result.refined.begin(), result.refined.end(), 1));
    }
}

std::uint64_t RefineJob::refined_pixels() const {
    const std::lock_guard lock(totals_mutex_);
    return refined_;
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
    return differing_.load(std::memory_order_relaxed);
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
    frame_ = std::thread([this, job = job_] { job->run(cancel_, threads_); });
}

void Refiner::stop() {
    cancel_ = true;
    if (frame_.joinable()) frame_.join();
    job_.reset();
}

} // namespace glint
