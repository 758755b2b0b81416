"""What to check when a wrong answer matches no catalogued mistake: one hint per exercise that has none of
its own, added to the generic message (which already says which entries, columns and rows are wrong)."""

from __future__ import annotations

HINTS: dict[str, str] = {
    "ch01_ex3": "Use [Ad_T_ab] = [[R, 0], [[p]R, R]] with R, p of T_ab; check the angular rows 1-3 (R ω_b) first, "
                "then the linear rows 4-6 ([p]R ω_b + R v_b).",
    "ch02_ex2": "Column 1 is S1; column 2 is Ad(e^[S1]θ1) S2; column 3 is Ad(e^[S1]θ1 e^[S2]θ2) S3 (joint 3 is "
                "prismatic: its ω is 0). Check the wrong column's joint and whether its axis was moved by the "
                "joints before it.",
    "ch03_ex1": "The column is the joint's screw axis seen from the tool frame {b} at this pose: its ω is z and its "
                "v is -ω × r with r the joint's position relative to the tool, written in {b}.",
    "ch03_ex2": "B = [Ad_M⁻¹] S, column by column: check the wrong column's joint and the linear rows 4-6, which "
                "change with the reference point.",
    "ch04_ex1": "J_b = [Ad_T_bs] J_s with T_bs = T_sb⁻¹ = [[Rᵀ, -Rᵀp], [0, 1]]; check the wrong column (joint) and "
                "whether the wrong entries are angular (rows 1-3) or linear (rows 4-6).",
    "ch04_ex2": "J_s = [Ad_T_sb] J_b; check the wrong column (joint) and whether the wrong entries are angular "
                "(rows 1-3) or linear (rows 4-6).",
    "ch05_ex2": "J = blockdiag(R_sb, R_sb) J_b, with R_sb the rotation block of T_sb; check the wrong column "
                "(joint) and half.",
    "ch05_ex3": "The column is (z_i, z_i × (p - p_i)): check the cross product entry by entry.",
    "ch06_ex3": "Only the angular rows change: J_a = blockdiag(B(φ)⁻¹, I) J. Check the wrong column (joint) and "
                "B(φ) at the given φ, in radians.",
    "ch06_ex5": "The angular block is B(φ)⁻¹ times the angular rows of the geometric Jacobian, at φ = θ; check "
                "the wrong column (joint).",
    "ch07_ex1": "Only the row order changes: rows 4-6 of J_Sic (ω) go on top. Check which rows you moved.",
    "ch07_ex2": "Reorder the rows to (ω, ṗ), then shift the reference point: v_s = ṗ + p × ω with p the tool "
                "position from T_sb. Check the linear rows 4-6 of the wrong column.",
    "ch07_ex3": "Reorder the rows to (ω, v), then express both halves in {b}: multiply each by R_sbᵀ. Check the "
                "wrong column (joint) and half.",
    "ch08_ex1": "Link 2 moves with joints 1 and 2 only: columns 1 and 2 are those of J_s, column 3 is zero. Check "
                "the wrong column.",
    "ch08_ex2": "Column i (i = 1, 2) is (z, z × (c - q_i)) with c the centre of link 2 and q_i joint i's position; "
                "column 3 is zero. Check the wrong column (joint).",
    "ch08_ex3": "M = Σ J_b,iᵀ G_i J_b,i over the two links, with G_i = blockdiag(I_i, m_i I) at the link's centre; "
                "check the entry's link contributions one by one.",
    "ch09_ex1": "τ = J_bᵀ F_b: entry i is column i of J_b dotted with F_b (moment first). Check the wrong "
                "entry's joint.",
    "ch09_ex2": "θ̇ = J_v⁺ ṗ with J_v⁺ = J_vᵀ(J_v J_vᵀ)⁻¹ and J_v the 2x3 position Jacobian (rows ẋ, ẏ). Check "
                "J_v's column for the wrong joint.",
    "ch09_ex3": "For a square J_v, w = |det J_v|, which for a planar 2R arm simplifies to the two link lengths "
                "times one sine: check J_v's entries (derivatives of x and y) and that the angles are in radians.",
    "ch01_ex4": "Compare your result block by block with the definition: the two diagonal blocks are rotations, "
                "the lower-left block couples them through the position.",
    "ch02_ex4": "Column i is Ad(e^[S1]θ1 ⋯ e^[S(i-1)]θ(i-1)) S_i: check the first wrong column's joint and the "
                "running product of exponentials up to it.",
    "ch03_ex4": "Column i is Ad(e^-[Bn]θn ⋯ e^-[B(i+1)]θ(i+1)) B_i: check the first wrong column's joint, walking "
                "from the last joint back.",
    "ch04_ex3": "The two Jacobians differ by the adjoint of T_sb or of its inverse: check the angular rows 1-3 "
                "(a rotation only) before the linear rows 4-6 (rotation plus the p × ω term).",
    "ch05_ex4": "J = blockdiag(R_sb, R_sb) J_b with R_sb the rotation of the tool at θ: check the angular rows "
                "1-3 first, then the linear rows 4-6.",
    "ch07_ex4": "Only the row order changes between the two conventions: check which rows hold ω.",
    "ch08_ex4": "Entry [i] keeps the columns of joints 1..i+1 of J_s and zeroes the rest: check the first wrong "
                "block's columns.",
    "ch09_ex4": "Solve (J Jᵀ + damping I) y = V and return Jᵀ y, with the damping squared or not as your variant "
                "says.",
    "ch09_ex5": "The semi-axes are the singular values of J_v (square roots of the eigenvalues of J_v J_vᵀ), "
                "longest first; check J_v at this pose.",
    "ch10_ex1": "V_b = log(T_sb⁻¹ T_sd) with T_sb⁻¹ = [[Rᵀ, -Rᵀp], [0, 1]]; V_s = [Ad_T_sb] V_b. Check ω first "
                "(rows 1-3: the axis times the angle of the relative rotation), then v (rows 4-6).",
    "ch10_ex2": "Compute p(θ_k) and J_v(θ_k) (columns ∂p/∂θ1, ∂p/∂θ2, angles in radians), solve J_v Δθ = p_d - p(θ_k), "
                "then add Δθ to θ_k in radians. Check the wrong entry's joint.",
    "ch10_ex3": "Build J_v at θ_k (angles in radians), e = p_d - p(θ_k), then solve (J_vᵀJ_v + λ²I) Δθ = J_vᵀe. Check "
                "the wrong entry's joint.",
    "ch10_ex4": "Per iterate: T = FK(θ); V from the logarithm of the transform in the order of your form; stop when "
                "‖ω‖ ≤ eps_omega and ‖v‖ ≤ eps_v; else θ += pinv(J) V with the Jacobian of the same frame; at most "
                "max_iterations steps (the argument, not a fixed number).",
}
