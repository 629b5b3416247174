// Enki's step over a grid (see partitioned_world.hpp).

#include "partitioned_world.hpp"

#include <algorithm>
#include <cmath>
#include <typeinfo>
#include <utility>

namespace aseba::arena
{
namespace
{

// How much nearer than their reach two objects are taken as a pair for the
// collision pass (cm), against the moves of the pass itself.
constexpr double collision_margin = 2;

// Enki's step calls the objects' protected hooks; a class derived from the
// object's class may name them, and calls through the member pointers are
// virtual as Enki's are.
struct ObjectHooks : Enki::PhysicalObject {
    using Hook = void (Enki::PhysicalObject::*)(double, Enki::World *);
    static constexpr Hook init_local = &ObjectHooks::initLocalInteractions;
    static constexpr Hook init_global = &ObjectHooks::initGlobalInteractions;
    static constexpr Hook with_walls = &ObjectHooks::doLocalWallsInteraction;
    static constexpr Hook global = &ObjectHooks::doGlobalInteractions;
    static constexpr Hook finalize_local = &ObjectHooks::finalizeLocalInteractions;
    static constexpr Hook finalize_global = &ObjectHooks::finalizeGlobalInteractions;
    static constexpr void (Enki::PhysicalObject::*with_object)(double,
                                                               Enki::World *,
                                                               Enki::PhysicalObject *) =
      &ObjectHooks::doLocalInteractions;
    static constexpr void (Enki::PhysicalObject::*control)(double) = &ObjectHooks::controlStep;
};

struct RobotInteractions : Enki::Robot {
    static const std::vector<Enki::LocalInteraction *> &of(const Enki::Robot &robot)
    {
        return robot.*(&RobotInteractions::localInteractions);
    }
};

// The physics hooks Enki's step calls are private to PhysicalObject (its
// friend is World itself, not a class derived from it). An explicit
// instantiation may name a private member (C++20 [temp.spec.general]/6): the
// template below hands its pointer out through a friend function.
template<typename Tag, typename Tag::Pointer member>
struct PrivateMember {
    friend typename Tag::Pointer pointer_to(Tag)
    {
        return member;
    }
};
struct InitPhysics {
    using Pointer = void (Enki::PhysicalObject::*)(double);
    friend Pointer pointer_to(InitPhysics);
};
struct FinalizePhysics {
    using Pointer = void (Enki::PhysicalObject::*)(double);
    friend Pointer pointer_to(FinalizePhysics);
};
template struct PrivateMember<InitPhysics, &Enki::PhysicalObject::initPhysicsInteractions>;
template struct PrivateMember<FinalizePhysics, &Enki::PhysicalObject::finalizePhysicsInteractions>;

// How far object `object`'s local interactions reach (Robot: its longest,
// Enki sorts them longest first); 0 for a plain object, which has none; -1
// when unknown.
double sensing_range(Enki::PhysicalObject *object)
{
    if (typeid(*object) == typeid(Enki::PhysicalObject))
        return 0;
    auto *robot = dynamic_cast<Enki::Robot *>(object);
    if (!robot)
        return -1;
    const auto &interactions = RobotInteractions::of(*robot);
    return interactions.empty() ? 0 : interactions.front()->getRange();
}

} // namespace

PartitionedWorld::PartitionedWorld(double width, double height, const Enki::Color &wall_color)
  : Enki::World(width, height, wall_color)
{
}

void PartitionedWorld::take_objects()
{
    objects_.assign(objects.begin(), objects.end());
    sensing_ranges_.resize(objects_.size());
    double longest_range = 0;
    for (size_t i = 0; i < objects_.size(); i++) {
        sensing_ranges_[i] = sensing_range(objects_[i]);
        longest_range = std::max(longest_range, sensing_ranges_[i]);
    }
    // Cells about as wide as the longest reach: a query looks at a few.
    cell_size_ = std::max({ longest_range, 2 * collision_margin, 1.0 });
    // An object no wider than a cell goes in the cell of its centre alone
    // (a query widens its cells by the largest such radius, and meets each
    // object once); a wider one (a large obstacle) is met by every query.
    grid_radius_ = 0;
    large_objects_.clear();
    for (size_t i = 0; i < objects_.size(); i++) {
        if (outside_grid(i))
            large_objects_.push_back(uint32_t(i));
        else
            grid_radius_ = std::max(grid_radius_, objects_[i]->getRadius());
    }
}

bool PartitionedWorld::outside_grid(size_t index) const
{
    return objects_[index]->getRadius() > cell_size_;
}

void PartitionedWorld::build_grid()
{
    // The walls bound the grid; an object pushed past them lands in a border
    // cell.
    columns_ = std::max(1L, long(std::ceil(w / cell_size_)));
    rows_ = std::max(1L, long(std::ceil(h / cell_size_)));
    // Counting sort of the objects by the cell of their centre, ascending
    // within a cell.
    cell_starts_.assign(size_t(columns_ * rows_) + 1, 0);
    object_cells_.resize(objects_.size());
    for (size_t i = 0; i < objects_.size(); i++) {
        const Enki::PhysicalObject *object = objects_[i];
        if (outside_grid(i)) {
            object_cells_[i] = UINT32_MAX;
            continue;
        }
        const size_t cell =
          size_t(cell_of(object->pos.y, rows_) * columns_ + cell_of(object->pos.x, columns_));
        object_cells_[i] = uint32_t(cell);
        cell_starts_[cell + 1]++;
    }
    for (size_t c = 1; c < cell_starts_.size(); c++)
        cell_starts_[c] += cell_starts_[c - 1];
    cell_objects_.resize(cell_starts_.back());
    cell_fill_.assign(cell_starts_.begin(), cell_starts_.end() - 1);
    for (size_t i = 0; i < objects_.size(); i++)
        if (object_cells_[i] != UINT32_MAX)
            cell_objects_[cell_fill_[object_cells_[i]]++] = uint32_t(i);
}

void PartitionedWorld::objects_near(size_t index, double reach, Query &query) const
{
    std::vector<uint32_t> &found = query.found;
    found.clear();
    const Enki::PhysicalObject *object = objects_[index];
    const double around = object->getRadius() + reach;
    // An object within reach has its centre within around + its radius; the
    // margin is far wider than the rounding of the cells' bounds.
    constexpr double margin = 1e-6;
    const double search = around + grid_radius_ + margin;
    const long x0 = cell_of(object->pos.x - search, columns_);
    const long x1 = cell_of(object->pos.x + search, columns_);
    const long y0 = cell_of(object->pos.y - search, rows_);
    const long y1 = cell_of(object->pos.y + search, rows_);
    auto meet = [&](uint32_t other) {
        const double within = around + objects_[other]->getRadius();
        if ((objects_[other]->pos - object->pos).norm2() <= within * within)
            found.push_back(other);
    };
    for (long y = y0; y <= y1; y++)
        for (long x = x0; x <= x1; x++) {
            const size_t cell = size_t(y * columns_ + x);
            for (uint32_t k = cell_starts_[cell]; k < cell_starts_[cell + 1]; k++)
                if (cell_objects_[k] != index)
                    meet(cell_objects_[k]);
        }
    for (uint32_t other : large_objects_)
        if (other != index)
            meet(other);
    std::sort(found.begin(), found.end());
}

void PartitionedWorld::collide_nearby_pairs()
{
    build_grid();
    std::vector<double> moved(objects_.size(), 0);
    for (size_t i = 0; i < objects_.size(); i++) {
        objects_near(i, collision_margin, query_);
        for (uint32_t j : query_.found) {
            if (j <= i)
                continue;
            Enki::PhysicalObject *first = objects_[i], *second = objects_[j];
            Enki::Point first_before = first->pos, second_before = second->pos;
            collideObjects(first, second);
            moved[i] += (first->pos - first_before).norm();
            moved[j] += (second->pos - second_before).norm();
        }
    }
    if (!moved.empty() && *std::max_element(moved.begin(), moved.end()) > collision_margin / 2)
        margin_overruns_++;
}

void PartitionedWorld::set_parallel_for(ParallelFor parallel_for)
{
    parallel_for_ = std::move(parallel_for);
}

void PartitionedWorld::sense_objects(double dt, size_t begin, size_t end, Query &query)
{
    for (size_t i = begin; i < end; i++) {
        Enki::PhysicalObject *object = objects_[i];
        double range = sensing_ranges_[i];
        (object->*ObjectHooks::init_local)(dt, this);
        if (range == 0)
            continue;
        if (range < 0) {
            for (size_t j = 0; j < objects_.size(); j++)
                if (j != i)
                    (object->*ObjectHooks::with_object)(dt, this, objects_[j]);
            continue;
        }
        objects_near(i, range, query);
        for (uint32_t j : query.found)
            (object->*ObjectHooks::with_object)(dt, this, objects_[j]);
    }
    if (wallsType != WALLS_NONE)
        for (size_t i = begin; i < end; i++)
            (objects_[i]->*ObjectHooks::with_walls)(dt, this);
}

void PartitionedWorld::sense_nearby_objects(double dt)
{
    build_grid();
    if (!parallel_for_) {
        sense_objects(dt, 0, objects_.size(), query_);
        return;
    }
    parallel_for_(objects_.size(), [this, dt](size_t begin, size_t end) {
        // A query of its own: pieces run at once on different threads.
        Query query;
        sense_objects(dt, begin, end, query);
    });
}

void PartitionedWorld::step(double dt, unsigned physics_oversampling)
{
    take_objects();
    const double physics_dt = dt / double(physics_oversampling);
    for (unsigned pass = 0; pass < physics_oversampling; pass++) {
        for (Enki::PhysicalObject *object : objects_)
            (object->*pointer_to(InitPhysics{}))(physics_dt);
        collide_nearby_pairs();
        for (Enki::PhysicalObject *object : objects_) {
            if (wallsType == WALLS_SQUARE)
                collideWithSquareWalls(object);
            else if (wallsType == WALLS_CIRCULAR)
                collideWithCircularWalls(object);
            (object->*pointer_to(FinalizePhysics{}))(physics_dt);
        }
    }
    // Enki starts an object's global interactions right after its local
    // ones; the two are apart (an e-puck has no global one), so the global
    // ones start first here, and the local ones with the sensing pass.
    for (Enki::PhysicalObject *object : objects_)
        (object->*ObjectHooks::init_global)(dt, this);
    sense_nearby_objects(dt);
    // The noise of the sensors and wheels draws from shared generators: one
    // object after the other, in Enki's order.
    for (Enki::PhysicalObject *object : objects_) {
        (object->*ObjectHooks::global)(dt, this);
        (object->*ObjectHooks::finalize_local)(dt, this);
        (object->*ObjectHooks::finalize_global)(dt, this);
        (object->*ObjectHooks::control)(dt);
    }
    controlStep(dt);
    if (bluetoothBase)
        bluetoothBase->step(dt, this);
}

} // namespace aseba::arena
