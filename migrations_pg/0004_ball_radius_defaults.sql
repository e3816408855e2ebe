-- PostgreSQL's version of migrations/0004_ball_radius_defaults.sql: the same schema and seed in PostgreSQL's
-- dialect (src/service/store.rs says how the two sets agree). Append-only, like migrations/.
-- Ball and radius end mills work with the database's defaults (MODEL.md §3, §5, §9).
-- Before this migration the seeded ball end mills had no standard side-cutting conditions and
-- no force model, so costing and feed optimisation refused them; the radius end mills carried
-- a copy of the square end mill's force model marked assumed. This migration adds, for every
-- seeded ball (D6, 8, 10, 12, 13, 16) and radius end mill, what those jobs need:
--   * the ball's standard side cut: seed 004 Table 7 for the R5 ball (D10), scaled at equal
--     cutting speed for the other diameters as 0002_seed.sql scales the ball rows;
--   * a force model derived from the square end mill's model of the same diameter by the
--     engaged cutting-edge length (ForceModel::carried_over, engaged_edge_length_mm in
--     src/core/force_model.rs), marked extrapolated; the radius rows are replaced by the same
--     rule (their corner arc plus the straight flank);
--   * the ball's tool-life rows (seeded in 0002) say which cut their 320 m refer to, and
--     their gamma table is 1 at that cut.
-- The values were computed once from those rules; tests/api/ball_tools.rs recomputes them.
-- A shop's rows are never touched: rows are only added where the tool (still of its seeded
-- shape) has none of the kind, and only unedited seeded rows are updated.

-- The ball's standard side cut: the reference of its force model, tool life and feed limits.
WITH v (d, spindle_rpm, fz_mm, fz_min_mm, rd_mm, ad_mm, source, reference) AS (VALUES
  (6, 16666.7, 0.18, 0.009, 2.4, 0.36, 'assumed', 'scaled from the R5 ball''s side cut of seed 004 Table 7 at equal cutting speed, as 0002 scales the ball rows: S x 10/D, fz, Rd, Ad x D/10; fz_min = 0.05 fz'),
  (8, 12500, 0.24, 0.012, 3.2, 0.48, 'assumed', 'scaled from the R5 ball''s side cut of seed 004 Table 7 at equal cutting speed, as 0002 scales the ball rows: S x 10/D, fz, Rd, Ad x D/10; fz_min = 0.05 fz'),
  (10, 10000, 0.3, 0.015, 4, 0.6, 'paper', 'seed 004 Table 7 (case study II, conventional strategy, R5 ball, 2 flutes: S 10000, fz 0.3, Ad 0.6, Rd 4.0), the ball''s side cut; Table 3''s fz 0.05 disagrees with Table 4 (MODEL.md §5); fz_min = 0.05 fz assumed'),
  (12, 8333.3, 0.36, 0.018, 4.8, 0.72, 'assumed', 'scaled from the R5 ball''s side cut of seed 004 Table 7 at equal cutting speed, as 0002 scales the ball rows: S x 10/D, fz, Rd, Ad x D/10; fz_min = 0.05 fz'),
  (13, 7692.3, 0.39, 0.0195, 5.2, 0.78, 'assumed', 'scaled from the R5 ball''s side cut of seed 004 Table 7 at equal cutting speed, as 0002 scales the ball rows: S x 10/D, fz, Rd, Ad x D/10; fz_min = 0.05 fz'),
  (16, 6250, 0.48, 0.024, 6.4, 0.96, 'assumed', 'scaled from the R5 ball''s side cut of seed 004 Table 7 at equal cutting speed, as 0002 scales the ball rows: S x 10/D, fz, Rd, Ad x D/10; fz_min = 0.05 fz')
)
INSERT INTO standard_conditions (tool_id, material_id, operation, spindle_rpm, fz_mm, fz_min_mm, fz_max_mm, rd_mm, ad_mm, ad_last_layer_mm, notes, source, reference, seed_key)
SELECT t.id, m.id, 'standard_side_cutting', v.spindle_rpm, v.fz_mm, v.fz_min_mm, NULL, v.rd_mm, v.ad_mm, NULL,
       'the ball''s side cut (contour-parallel roughing in thin layers, seed 004 case study II); reference conditions of its force model and tool life',
       v.source, v.reference, 'conditions:ball-' || v.d || ':skd61:standard_side_cutting'
FROM v
JOIN tools t ON t.seed_key = 'tool:ball-' || v.d AND t.tool_type = 'ball' AND abs(t.diameter_mm - v.d) < 1e-9
JOIN materials m ON m.seed_key = 'material:skd61'
WHERE NOT EXISTS (SELECT 1 FROM standard_conditions c
                  WHERE c.tool_id = t.id AND c.material_id = m.id AND c.operation = 'standard_side_cutting');

-- The ball's force model, where the tool has none yet.
WITH v (d, t0_um, dt_um, l0_mm, dl_mm, b0, b1, b2, b22, b12, ad_ref_mm, reference) AS (VALUES
  (6, 17.435596, 7, 1.35308, 0.262, 6.91587953, 1.9467409, 1.48562727, 0.124145977, 0.480168592, 0.36, 'the square D6 model (seed 001 Table 4) carried over to the 2-flute ball by the engaged cutting-edge length: every beta x (2/6 flutes) x e(Ad_ref)/6, e = R acos(1 - Ad/R) the edge the ball (R 3) engages at Ad_ref 0.36 mm (its standard Ad) = x 0.0824890; t0, dt, L0, dL of the square model; forces scale with e(Ad)/e(Ad_ref) (src/core/force_model.rs)'),
  (8, 30.512293, 11, 1.804107, 0.349, 13.4457104, 3.56847505, 2.79885248, 0.217276081, 0.692907777, 0.48, 'the square D8 model (seed 001 Table 4) carried over to the 2-flute ball by the engaged cutting-edge length: every beta x (2/6 flutes) x e(Ad_ref)/8, e = R acos(1 - Ad/R) the edge the ball (R 4) engages at Ad_ref 0.48 mm (its standard Ad) = x 0.0824890; t0, dt, L0, dL of the square model; forces scale with e(Ad)/e(Ad_ref) (src/core/force_model.rs)'),
  (10, 43.588989, 15, 2.255134, 0.436, 22.1977956, 5.43107715, 4.42636087, 0.310406186, 1.27445538, 0.6, 'the square D10 model (seed 001 Table 4) carried over to the 2-flute ball by the engaged cutting-edge length: every beta x (2/6 flutes) x e(Ad_ref)/10, e = R acos(1 - Ad/R) the edge the ball (R 5) engages at Ad_ref 0.6 mm (its standard Ad) = x 0.0824890; t0, dt, L0, dL of the square model; forces scale with e(Ad)/e(Ad_ref) (src/core/force_model.rs)'),
  (12, 43.588989, 18, 2.706161, 0.5232, 31.9648256, 7.82075109, 6.37395965, 0.446984908, 1.83521574, 0.72, 'the square D12 model (itself the 10 mm model of seed 001 Table 4 scaled by (D/10)^2) carried over to the 2-flute ball by the engaged cutting-edge length: every beta x (2/6 flutes) x e(Ad_ref)/12, e = R acos(1 - Ad/R) the edge the ball (R 6) engages at Ad_ref 0.72 mm (its standard Ad) = x 0.0824890; t0, dt, L0, dL of the square model; forces scale with e(Ad)/e(Ad_ref) (src/core/force_model.rs)'),
  (13, 43.588989, 19.5, 2.931674, 0.5668, 37.5142745, 9.17852038, 7.48054987, 0.524586455, 2.15382958, 0.78, 'the square D13 model (itself the 10 mm model of seed 001 Table 4 scaled by (D/10)^2) carried over to the 2-flute ball by the engaged cutting-edge length: every beta x (2/6 flutes) x e(Ad_ref)/13, e = R acos(1 - Ad/R) the edge the ball (R 6.5) engages at Ad_ref 0.78 mm (its standard Ad) = x 0.0824890; t0, dt, L0, dL of the square model; forces scale with e(Ad)/e(Ad_ref) (src/core/force_model.rs)'),
  (16, 43.588989, 24, 3.608214, 0.6976, 56.8263566, 13.9035575, 11.3314838, 0.794639837, 3.26260576, 0.96, 'the square D16 model (itself the 10 mm model of seed 001 Table 4 scaled by (D/10)^2) carried over to the 2-flute ball by the engaged cutting-edge length: every beta x (2/6 flutes) x e(Ad_ref)/16, e = R acos(1 - Ad/R) the edge the ball (R 8) engages at Ad_ref 0.96 mm (its standard Ad) = x 0.0824890; t0, dt, L0, dL of the square model; forces scale with e(Ad)/e(Ad_ref) (src/core/force_model.rs)')
)
INSERT INTO force_models (tool_id, material_id, t0_um, dt_um, l0_mm, dl_mm, b0, b1, b2, b11, b22, b12, r_squared, ad_ref_mm, source, reference, seed_key)
SELECT t.id, m.id, v.t0_um, v.dt_um, v.l0_mm, v.dl_mm, v.b0, v.b1, v.b2, 0, v.b22, v.b12, NULL, v.ad_ref_mm,
       'extrapolated', v.reference, 'force_model:ball-' || v.d || ':skd61'
FROM v
JOIN tools t ON t.seed_key = 'tool:ball-' || v.d AND t.tool_type = 'ball' AND abs(t.diameter_mm - v.d) < 1e-9
            AND t.flutes = 2 AND abs(t.corner_radius_mm - v.d / 2.0) < 1e-9
JOIN materials m ON m.seed_key = 'material:skd61'
WHERE NOT EXISTS (SELECT 1 FROM force_models f WHERE f.tool_id = t.id AND f.material_id = m.id);

-- The radius end mill's force model: the same rule, in place of the copy of the square's,
-- where the row is unedited and the tool still of its seeded shape.
WITH v (d, corner_radius_mm, b0, b1, b2, b22, b12, reference) AS (VALUES
  (6, 0.5, 87.8279637, 24.7225661, 18.8666702, 1.57658737, 6.09788378, 'the square D6 model (seed 001 Table 4) carried over to the radius end mill by the engaged cutting-edge length: every beta x e(Ad_ref)/6, e = rc pi/2 + (Ad - rc) the corner arc (rc 0.5) and flank engaged at Ad_ref 6 mm = x 1.0475664; 6 flutes as the square; t0, dt, L0, dL of the square model; forces scale with e(Ad)/e(Ad_ref) (src/core/force_model.rs)'),
  (8, 0.5, 168.814988, 44.8032906, 35.140445, 2.72796735, 8.69966807, 'the square D8 model (seed 001 Table 4) carried over to the radius end mill by the engaged cutting-edge length: every beta x e(Ad_ref)/8, e = rc pi/2 + (Ad - rc) the corner arc (rc 0.5) and flank engaged at Ad_ref 8 mm = x 1.0356748; 6 flutes as the square; t0, dt, L0, dL of the square model; forces scale with e(Ad)/e(Ad_ref) (src/core/force_model.rs)'),
  (10, 1, 284.460129, 69.598123, 56.7228931, 3.97779066, 16.3318803, 'the square D10 model (seed 001 Table 4) carried over to the radius end mill by the engaged cutting-edge length: every beta x e(Ad_ref)/10, e = rc pi/2 + (Ad - rc) the corner arc (rc 1) and flank engaged at Ad_ref 10 mm = x 1.0570796; 6 flutes as the square; t0, dt, L0, dL of the square model; forces scale with e(Ad)/e(Ad_ref) (src/core/force_model.rs)'),
  (12, 1, 405.936155, 99.3193476, 80.9458717, 5.67646879, 23.3062564, 'the square D12 model (itself the 10 mm model of seed 001 Table 4 scaled by (D/10)^2) carried over to the radius end mill by the engaged cutting-edge length: every beta x e(Ad_ref)/12, e = rc pi/2 + (Ad - rc) the corner arc (rc 1) and flank engaged at Ad_ref 12 mm = x 1.0475664; 6 flutes as the square; t0, dt, L0, dL of the square model; forces scale with e(Ad)/e(Ad_ref) (src/core/force_model.rs)'),
  (13, 1, 474.747168, 116.15516, 94.667161, 6.63869786, 27.2569444, 'the square D13 model (itself the 10 mm model of seed 001 Table 4 scaled by (D/10)^2) carried over to the radius end mill by the engaged cutting-edge length: every beta x e(Ad_ref)/13, e = rc pi/2 + (Ad - rc) the corner arc (rc 1) and flank engaged at Ad_ref 13 mm = x 1.0439074; 6 flutes as the square; t0, dt, L0, dL of the square model; forces scale with e(Ad)/e(Ad_ref) (src/core/force_model.rs)'),
  (16, 1, 713.472207, 174.563397, 142.270229, 9.97694505, 40.9630085, 'the square D16 model (itself the 10 mm model of seed 001 Table 4 scaled by (D/10)^2) carried over to the radius end mill by the engaged cutting-edge length: every beta x e(Ad_ref)/16, e = rc pi/2 + (Ad - rc) the corner arc (rc 1) and flank engaged at Ad_ref 16 mm = x 1.0356748; 6 flutes as the square; t0, dt, L0, dL of the square model; forces scale with e(Ad)/e(Ad_ref) (src/core/force_model.rs)')
)
UPDATE force_models
SET b0 = v.b0, b1 = v.b1, b2 = v.b2, b22 = v.b22, b12 = v.b12, r_squared = NULL, source = 'extrapolated',
    reference = v.reference, updated_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now')
FROM v
JOIN tools t ON t.seed_key = 'tool:radius-' || v.d AND t.tool_type = 'radius' AND t.flutes = 6
            AND abs(t.diameter_mm - v.d) < 1e-9 AND abs(t.corner_radius_mm - v.corner_radius_mm) < 1e-9
WHERE force_models.seed_key = 'force_model:radius-' || v.d || ':skd61' AND force_models.edited = 0
  AND force_models.tool_id = t.id;

-- The ball's tool life: what its 320 m refer to now that it has a standard cut, and a
-- gamma table that is 1 at that cut (the value of the life stays assumed).
UPDATE tool_life
SET gamma_table = '[[0, 1], [78.5, 1], [88.5, 2], [98.5, 4], [128.5, 8], [180, 10.3]]',
    reference = 'life 320 m of machined length at the ball''s standard side cut (standard_side_cutting), assumed as the 10 mm straight end mill of seed 003 until measured (seed 004 Fig. 12: the R5 ball showed V_b 0.1 mm and a small chipping after the 153.9 m of case study I); gamma: the shape of seed 002 §2.4 (1, then rising steeply) with its knee moved from 40 deg to the engagement of the ball''s standard cut in the 2.5-D model, 78.5 deg (Rd = 0.4 D: acos(1 - 0.8)), so that cut wears at the rate of the life: the straight end mill''s table shifted by 38.5 deg and cut at 180 deg; k = 2.4; all assumed (MODEL.md §9)',
    updated_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now')
WHERE seed_key IN ('tool_life:ball-6:skd61', 'tool_life:ball-8:skd61', 'tool_life:ball-10:skd61',
                   'tool_life:ball-12:skd61', 'tool_life:ball-13:skd61', 'tool_life:ball-16:skd61')
  AND edited = 0;
