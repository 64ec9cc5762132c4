-- The ashlar model library: each generator takes one option table and returns
-- a Structure with its supports set. Read them, copy them, make your own.
return {
  arch = require "ashlar.models.arch",
  barrel_vault = require "ashlar.models.barrel_vault",
  wall = require "ashlar.models.wall",
}
