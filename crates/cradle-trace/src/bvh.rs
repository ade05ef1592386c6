//! A bounding volume hierarchy over the bounded objects: secondary rays (shadows,
//! reflections) visit only the boxes they pass through, near side first, instead
//! of every object's box. Built each frame (the balls move), by median splits of
//! the box centres along the widest axis: O(n log n), tens of microseconds for
//! the default cradle.

use super::geometry::{Aabb, Ray};
use glam::Vec3;

/// Objects per leaf at most.
const LEAF: usize = 2;

#[derive(Debug, Clone, Copy)]
struct Node {
    bounds: Aabb,
    /// Leaf: its items are `order[first..first + count]`; inner: `count == 0`, its
    /// children are the next node and `right`.
    first: u32,
    count: u32,
    right: u32,
    /// Axis of the split (inner nodes): the near child is visited first.
    axis: u8,
}

/// The hierarchy; items are positions in the list it was built from.
#[derive(Debug, Clone, Default)]
pub struct Bvh {
    nodes: Vec<Node>,
    order: Vec<usize>,
}

impl Bvh {
    /// Builds over `boxes` (item `k` is `boxes[k]`).
    #[must_use]
    pub fn new(boxes: &[Aabb]) -> Self {
        let mut bvh = Self {
            nodes: Vec::with_capacity(2 * boxes.len()),
            order: (0..boxes.len()).collect(),
        };
        if !boxes.is_empty() {
            bvh.build(boxes, 0, boxes.len());
        }
        bvh
    }

    fn build(&mut self, boxes: &[Aabb], first: usize, count: usize) -> usize {
        let items = &mut self.order[first..first + count];
        let bounds = items.iter().fold(Aabb::EMPTY, |b, &k| b.union(boxes[k]));
        let at = self.nodes.len();
        self.nodes.push(Node {
            bounds,
            first: first as u32,
            count: count as u32,
            right: 0,
            axis: 0,
        });
        if count <= LEAF {
            return at;
        }
        let centre = |k: usize| (boxes[k].min + boxes[k].max) * 0.5;
        let (lo, hi) = items.iter().fold(
            (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
            |(lo, hi), &k| (lo.min(centre(k)), hi.max(centre(k))),
        );
        let extent = hi - lo;
        let axis = if extent.x >= extent.y && extent.x >= extent.z {
            0
        } else if extent.y >= extent.z {
            1
        } else {
            2
        };
        // Sorted by centre, ties by item, so the tree is the same on every run.
        items.sort_by(|&a, &b| centre(a)[axis].total_cmp(&centre(b)[axis]).then(a.cmp(&b)));
        let half = count / 2;
        self.nodes[at].count = 0;
        self.nodes[at].axis = axis as u8;
        self.build(boxes, first, half);
        let right = self.build(boxes, first + half, count - half);
        self.nodes[at].right = right as u32;
        at
    }

    /// Calls `visit(item)` for the items of every leaf whose box the ray meets
    /// before `limit()` (asked again at each node, so a closer hit prunes the rest),
    /// near side first. Stops and returns true as soon as `visit` does.
    pub fn traverse(
        &self,
        ray: &Ray,
        inv: Vec3,
        mut limit: impl FnMut() -> f32,
        mut visit: impl FnMut(usize) -> bool,
    ) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        let mut stack = [0u32; 64];
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let node = &self.nodes[stack[top] as usize];
            if !node.bounds.hit(ray, inv, limit()) {
                continue;
            }
            if node.count > 0 {
                let items = &self.order[node.first as usize..(node.first + node.count) as usize];
                for &k in items {
                    if visit(k) {
                        return true;
                    }
                }
                continue;
            }
            let left = stack[top] + 1;
            let (near, far) = if ray.dir[node.axis as usize] >= 0.0 {
                (left, node.right)
            } else {
                (node.right, left)
            };
            // Depth is at most log2(objects) + 1 < 32 for any scene the config
            // allows, so two more entries always fit.
            stack[top] = far;
            stack[top + 1] = near;
            top += 2;
        }
        false
    }
}
