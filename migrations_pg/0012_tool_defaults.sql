-- PostgreSQL's version of migrations/0012_tool_defaults.sql.
-- Default tools (issue 30, item 6). A request that names its tool by tool_type and
-- diameter_mm takes the default tool of that type and diameter, so a shop that adds a
-- second tool of a size no longer makes those requests ambiguous.
--   is_default  1 for the one default tool of its type and diameter (0 for the others).
-- One default per type and diameter, enforced by a partial unique index; diameters that
-- agree to 6 decimals are one diameter (src/service/resources/tools.rs uses the same
-- expression). The seeded tools are the defaults; where a type and diameter has no seeded
-- tool, its oldest tool is.
ALTER TABLE tools ADD COLUMN is_default BIGINT NOT NULL DEFAULT 0 CHECK (is_default IN (0, 1));

-- The oldest seeded tool of each type and diameter (PostgreSQL's DISTINCT ON in place of
-- SQLite's correlated subquery per group, which PostgreSQL refuses on an ungrouped column).
UPDATE tools SET is_default = 1
WHERE id IN (
    SELECT DISTINCT ON (tool_type, round(diameter_mm, 6)) id FROM tools
    ORDER BY tool_type, round(diameter_mm, 6), seed_key IS NULL, created_at, id
);

CREATE UNIQUE INDEX tools_one_default ON tools (tool_type, round(diameter_mm, 6)) WHERE is_default = 1;
