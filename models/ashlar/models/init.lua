-- The ashlar model library: each generator takes one option table and returns
-- a Structure with its supports set. Read them, copy them, make your own.
-- models.arc{} is an error that suggests models.arch.
return require("ashlar").strict({
  arch = require "ashlar.models.arch",
  barrel_vault = require "ashlar.models.barrel_vault",
  groin_vault = require "ashlar.models.groin_vault",
  dome = require "ashlar.models.dome",
  wall = require "ashlar.models.wall",
  column = require "ashlar.models.column",
  stack = require "ashlar.models.stack",
  post_and_lintel = require "ashlar.models.post_and_lintel",
  h_frame = require "ashlar.models.h_frame",
  flying_buttress = require "ashlar.models.flying_buttress",
  buttressed_vault = require "ashlar.models.buttressed_vault",
  arch_bridge = require "ashlar.models.arch_bridge",
  cable_stayed_bridge = require "ashlar.models.cable_stayed_bridge",
  perturbed = require "ashlar.models.perturbed",
}, "models")
